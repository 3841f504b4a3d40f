"""Rays against the exact shapes of the scene's parts, as 1.0's raycaster met them.

:class:`RayTargets` holds the shape of every physical part (:mod:`server.core.physics.rayshapes`)
at its world pose, with the ground plane y = 0 (met from above only), and answers for
many rays at once: per ray and per lower limit, the first thing met at or beyond that
limit, and how far (a sensor asks for two limits: 0 for touch, 0.05 for distance). No
engine, no collision margin: distances are exact to rounding.

Rays are tested against bounding spheres first; the pairs that pass are met exactly, all
pairs of one shape in one numpy call.
"""

from __future__ import annotations

from itertools import chain
from typing import Any, Sequence

import numpy as np

from ..kit.math3d import Pose
from .assets import AssetLibrary
from .rayshapes import GROUND_SHAPE, Convex, Shape, convex_entries_of, shape_of

GROUND = "ground"
_NOTHING, _GROUND = -2, -1  # key indices besides the rows of parts
_BROAD_CHUNK = 250_000  # ray × part pairs tested at once (bounded memory)
_SLACK = 1e-9  # relative and absolute: bounding spheres are met a hair generously
_ROW_SETS_KEPT = 4096  # sets of keys whose rows are kept (_rows_of)

Hits = tuple[list[list[str]], np.ndarray]  # keys (rays × limits), distances (rays, limits)


class RayTargets:
    """The shapes of physical parts at their world poses, keyed by node id."""

    def __init__(self, assets: AssetLibrary) -> None:
        self._assets = assets
        self._shapes: list[Shape] = []        # one per distinct geometry
        self._shape_index: dict[tuple, int] = {}
        self._keys: list[str] = []
        self._rows: dict[str, int] = {}
        self._shape_of = np.empty(0, dtype=np.int64)  # per row: index into _shapes
        self._rotations = np.empty((0, 3, 3))
        self._positions = np.empty((0, 3))
        self._centres = np.empty((0, 3))  # of the bounding spheres, in the world
        self._local_centres = np.empty((0, 3))  # the same in each part's own frame
        self._radii = np.empty(0)
        self._moved: dict[str, Pose] = {}  # poses not yet taken into the arrays
        self._kept_rows: dict[tuple[str, ...], np.ndarray] = {}  # (_rows_of)
        self._planes = ConvexPlanes()  # the convex shapes' planes, met in one go
        self._reach_kept: tuple[float, np.ndarray, np.ndarray] | None = None  # (_reach)

    def __len__(self) -> int:
        return len(self._keys)

    def __contains__(self, key: str) -> bool:
        return key in self._rows

    def add(self, key: str, geometry: dict[str, Any], pose: Pose) -> None:
        """A part's shape, placed at ``pose``."""
        shape_key = _shape_key(geometry)
        index = self._shape_index.get(shape_key)
        if index is None:
            index = self._shape_index[shape_key] = len(self._shapes)
            self._shapes.append(shape_of(geometry, self._assets))
            self._planes.add(index, self._shapes[index])
        self._rows[key] = len(self._keys)
        self._keys.append(key)
        self._shape_of = np.append(self._shape_of, index)
        self._rotations = np.concatenate([self._rotations, np.eye(3)[None]])
        self._positions = np.concatenate([self._positions, np.zeros((1, 3))])
        self._centres = np.concatenate([self._centres, np.zeros((1, 3))])
        self._local_centres = np.concatenate([self._local_centres, self._shapes[index].centre[None]])
        self._radii = np.append(self._radii, self._shapes[index].radius)
        self._reach_kept = None
        self.move(key, pose)

    def move(self, key: str, pose: Pose) -> None:
        """Place ``key``'s shape at a world pose (taken in when rays are next cast)."""
        self._moved[key] = pose

    def place_trees(self, trees: Sequence[tuple[tuple[str, ...], np.ndarray]]) -> None:
        """Place at once the shapes of whole trees: each a tuple of keys and their world
        poses as rows of seven numbers (position, quaternion), as
        :meth:`~server.core.physics.engine.PhysicsWorld.part_pose_rows` gives them."""
        self._place_moved()  # poses moved one by one before these: these are newer
        if trees:
            self._place(np.concatenate([self._rows_of(keys) for keys, _ in trees]),
                        np.concatenate([poses for _, poses in trees]))

    def _rows_of(self, keys: tuple[str, ...]) -> np.ndarray:
        """The rows of keys asked for together each tick (a tree's parts, the parts
        carrying the watched sensors), kept until a row moves (:meth:`remove`)."""
        rows = self._kept_rows.get(keys)
        if rows is None:
            if len(self._kept_rows) >= _ROW_SETS_KEPT:  # (trees built again make new sets)
                self._kept_rows.clear()
            rows = self._kept_rows[keys] = np.fromiter(
                map(self._rows.__getitem__, keys), np.int64, len(keys))
        return rows

    def frames(self, keys: tuple[str, ...]) -> tuple[np.ndarray, np.ndarray]:
        """World positions (n×3) and rotation matrices (n×3×3) of these keys' shapes, as
        placed (what sensors on the parts start from)."""
        self._place_moved()
        rows = self._rows_of(keys)
        return self._positions[rows], self._rotations[rows]

    def _place_moved(self) -> None:
        """Rotations, positions and sphere centres of the moved rows, in one go."""
        count = len(self._moved)
        if not count:
            return
        rows = np.fromiter(map(self._rows.__getitem__, self._moved), np.int64, count)
        # one conversion of every moved pose's seven numbers (a list of tuples per array,
        # as numpy reads nested sequences, took twice as long)
        poses = np.fromiter(chain.from_iterable(p + q for p, q in self._moved.values()),
                            float, 7 * count).reshape(count, 7)
        self._moved.clear()
        self._place(rows, poses)

    def _place(self, rows: np.ndarray, poses: np.ndarray) -> None:
        """Rotations, positions and sphere centres of ``rows`` from their poses (n×7)."""
        positions, rotations = poses[:, :3], _matrices(poses[:, 3:])
        self._rotations[rows] = rotations
        self._positions[rows] = positions
        self._centres[rows] = np.einsum("kij,kj->ki", rotations, self._local_centres[rows]) + positions

    def remove(self, key: str) -> None:
        """Forget ``key``'s shape (the last row takes its place)."""
        self._moved.pop(key, None)
        self._place_moved()
        row, last = self._rows.pop(key), len(self._keys) - 1
        self._kept_rows.clear()
        self._reach_kept = None
        arrays = (self._shape_of, self._rotations, self._positions, self._centres, self._radii,
                  self._local_centres)
        if row != last:
            moved = self._keys[last]
            self._keys[row] = moved
            self._rows[moved] = row
            for array in arrays:
                array[row] = array[last]
        self._keys.pop()
        (self._shape_of, self._rotations, self._positions, self._centres, self._radii,
         self._local_centres) = (array[:last] for array in arrays)

    def first_hits(self, origin: Sequence[float], direction: Sequence[float],
                   limits: Sequence[float], far: float) -> list[tuple[str, float]]:
        """For one ray: per limit, ``(key, distance)`` of the first hit, or ``("", inf)``."""
        keys, distances = self.cast(np.array([origin], float), np.array([direction], float),
                                    limits, far)
        return [(key, float(t)) for key, t in zip(keys[0], distances[0])]

    def distances(self, origins: np.ndarray, directions: np.ndarray, limits: Sequence[float],
                  far: float) -> np.ndarray:
        """For many rays (unit directions): per ray and limit, how far the first thing met
        at or beyond the limit lies, no farther than ``far`` (``inf``: nothing); as
        :meth:`cast` without naming what is met (sensing needs only how far)."""
        self._place_moved()
        best = GROUND_SHAPE.entries(origins, directions, limits)
        for rays, _, entries in self._exact(origins, directions, limits):
            np.minimum.at(best, rays, entries)
        best[best > far] = np.inf
        return best

    def cast(self, origins: np.ndarray, directions: np.ndarray, limits: Sequence[float],
             far: float) -> Hits:
        """For many rays (unit directions): per ray and limit, what is met first at or
        beyond the limit and no farther than ``far``, and its distance (``inf``: nothing)."""
        self._place_moved()
        best = GROUND_SHAPE.entries(origins, directions, limits)
        who = np.where(np.isfinite(best), _GROUND, _NOTHING)
        for rays, rows, entries in self._exact(origins, directions, limits):
            for k in range(len(limits)):
                _improve(best[:, k], who[:, k], rays, rows, entries[:, k])
        best[best > far] = np.inf
        who[best == np.inf] = _NOTHING
        names = [*self._keys, "", GROUND]  # so that _NOTHING and _GROUND index the last two
        return [[names[i] for i in row] for row in who.tolist()], best

    def _exact(self, origins: np.ndarray, directions: np.ndarray, limits: Sequence[float]):
        """(rays, rows, entries) for the pairs whose bounding sphere meets: every convex
        shape's pairs at once, then the other shapes one by one."""
        rays, rows = self._broad(origins, directions, limits[0])
        if not len(rays):
            return
        # local = Rᵀ (world - position), directions and origins side by side: one batched
        # product for both, in the form the convex shapes' planes take them
        world = np.stack((directions[rays], origins[rays] - self._positions[rows]), axis=2)
        local = self._rotations[rows].transpose(0, 2, 1) @ world  # (pairs, 3, 2)
        shapes = self._shape_of[rows]
        convex = self._planes.holds(shapes)
        if convex.all():
            yield rays, rows, convex_entries_of(*self._planes.of(shapes), local, limits)
            return
        if convex.any():
            yield rays[convex], rows[convex], convex_entries_of(
                *self._planes.of(shapes[convex]), local[convex], limits)
        others = ~convex
        local_o, local_d = local[..., 1], local[..., 0]
        for index in np.unique(shapes[others]):
            mine = others & (shapes == index)
            yield rays[mine], rows[mine], self._shapes[index].entries(local_o[mine],
                                                                      local_d[mine], limits)

    def _reach(self, low: float) -> tuple[np.ndarray, np.ndarray]:
        """Per row: the square of its bounding sphere's radius, a hair generous (rounding
        stays safe), and how far along a ray its centre may lie before ``low`` and still
        be met; kept until a row comes or goes (each tick asks for the same)."""
        kept = self._reach_kept
        if kept is None or kept[0] != low:
            reach = self._radii * (1 + _SLACK) + _SLACK
            kept = self._reach_kept = (low, reach ** 2, low - reach)
        return kept[1], kept[2]

    def _broad(self, origins: np.ndarray, directions: np.ndarray,
               low: float) -> tuple[np.ndarray, np.ndarray]:
        """Ray and row indices of the pairs whose bounding sphere lies on the ray past ``low``."""
        count = len(self._keys)
        if not count:
            return np.empty(0, np.int64), np.empty(0, np.int64)
        step = max(1, _BROAD_CHUNK // count)
        wide, short = self._reach(low)
        # with t = c - o: along = t·d, miss² = t·t - along²; both as one product of
        # matrices each, the ray's terms and the centre's side by side ([d, -o·d]·[c, 1] and
        # [-2o, o·o, 1]·[c, 1, c·c]): no rays × parts array but the two results (half the
        # time of products and broadcast sums at 100 rays and 160 parts)
        spheres = np.empty((5, count))
        spheres[:3], spheres[3], spheres[4] = self._centres.T, 1.0, (self._centres ** 2).sum(axis=1)
        found = []  # flat indices into rays × parts
        for start in range(0, len(origins), step):
            o, d = origins[start:start + step], directions[start:start + step]
            terms = np.empty((len(o), 5))
            terms[:, :3], terms[:, 3] = d, -np.einsum("rj,rj->r", o, d)
            along = terms[:, :4] @ spheres[:4]
            terms[:, :3], terms[:, 3], terms[:, 4] = -2 * o, np.einsum("rj,rj->r", o, o), 1.0
            miss = terms @ spheres
            miss -= along * along
            near = miss <= wide
            near &= along >= short
            # flat indices: a fifth of the time np.nonzero takes for a 2-D array
            found.append(np.flatnonzero(near) + start * count)
        pairs = found[0] if len(found) == 1 else np.concatenate(found)
        return np.divmod(pairs, count)


class ConvexPlanes:
    """The face planes of every convex shape, padded to one count: slot k of shape index
    i holds its normals and offsets (rows of zeros with offset 1 pad: no plane)."""

    def __init__(self) -> None:
        self._slot = np.empty(0, dtype=np.int64)  # per shape index; -1: not convex
        self._normals = np.zeros((0, 0, 3))
        self._offsets = np.ones((0, 0))

    def add(self, index: int, shape: Shape) -> None:
        """Note shape ``index`` (the next one); its planes if it is convex."""
        if not isinstance(shape, Convex):
            self._slot = np.append(self._slot, -1)
            return
        self._slot = np.append(self._slot, len(self._normals))
        width = max(self._normals.shape[1], len(shape.offsets))
        normals = np.zeros((len(self._normals) + 1, width, 3))
        offsets = np.ones((len(self._normals) + 1, width))
        normals[:-1, :self._normals.shape[1]] = self._normals
        offsets[:-1, :self._offsets.shape[1]] = self._offsets
        normals[-1, :len(shape.offsets)], offsets[-1, :len(shape.offsets)] = \
            shape.normals, shape.offsets
        self._normals, self._offsets = normals, offsets

    def holds(self, shapes: np.ndarray) -> np.ndarray:
        """Which of these shape indices are convex."""
        return self._slot[shapes] >= 0

    def of(self, shapes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Normals (k, planes, 3) and offsets (k, planes) of these convex shape indices."""
        slots = self._slot[shapes]
        return self._normals[slots], self._offsets[slots]


def _improve(best: np.ndarray, who: np.ndarray, rays: np.ndarray, rows: np.ndarray,
             entries: np.ndarray) -> None:
    """Lower ``best`` (and ``who``) per ray where one of the pairs' entries is nearer."""
    found = np.isfinite(entries)
    rays, rows, entries = rays[found], rows[found], entries[found]
    order = np.lexsort((rows, entries, rays))  # per ray: nearest first (ties: older row)
    rays, rows, entries = rays[order], rows[order], entries[order]
    first = np.ones(len(rays), bool)
    first[1:] = rays[1:] != rays[:-1]
    rays, rows, entries = rays[first], rows[first], entries[first]
    nearer = entries < best[rays]
    best[rays[nearer]] = entries[nearer]
    who[rays[nearer]] = rows[nearer]


def _matrices(q: np.ndarray) -> np.ndarray:
    """Rotation matrices of unit quaternions (x, y, z, w), as math3d.to_matrix, many at once:
    each entry is 1, 0 or ± a sum of two of the products 2·qi·qj, so all nine come from the
    sixteen products by one product of matrices (a third of the time of nine expressions)."""
    count = len(q)
    products = (2 * q[:, :, None] * q[:, None, :]).reshape(count, 16)
    return (products @ _PRODUCTS_TO_MATRIX + _IDENTITY).reshape(count, 3, 3)


def _products_to_matrix() -> np.ndarray:
    """(16, 9): which products 2·qi·qj (row 4i + j; x, y, z, w = 0 … 3) add up to which
    entry of the row-major rotation matrix, and with which sign."""
    terms = {0: "-yy -zz", 1: "+xy -zw", 2: "+xz +yw", 3: "+xy +zw", 4: "-xx -zz", 5: "+yz -xw",
             6: "+xz -yw", 7: "+yz +xw", 8: "-xx -yy"}
    index = {axis: k for k, axis in enumerate("xyzw")}
    table = np.zeros((16, 9))
    for entry, sums in terms.items():
        for term in sums.split():
            table[4 * index[term[1]] + index[term[2]], entry] = 1.0 if term[0] == "+" else -1.0
    return table


_PRODUCTS_TO_MATRIX = _products_to_matrix()
_IDENTITY = np.eye(3).reshape(9)


def _shape_key(geometry: dict[str, Any]) -> tuple:
    """What makes two geometries one shape (colours do not, nor a mesh's envelope)."""
    ignored = {"color", "edges"} | ({"points"} if geometry["kind"] == "mesh" else set())

    def frozen(value: Any) -> Any:
        return tuple(frozen(v) for v in value) if isinstance(value, list) else value
    return tuple((k, frozen(v)) for k, v in sorted(geometry.items()) if k not in ignored)
