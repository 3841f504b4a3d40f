"""The shapes rays meet: sphere, convex hull (boxes too) and mesh in a part's own frame, and the ground.

Each meets many rays at once (numpy) and answers, per ray and per lower limit, the first
distance at which the ray enters a *front* face at or beyond that limit (``inf`` for
none). Only front faces count, so a ray that starts inside a shape never sees it; a ray
starting on a face (within ``ON_SURFACE``) meets it at 0. Directions are unit vectors.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any, Protocol, Sequence

import numpy as np

from .assets import AssetLibrary, placed
from .geometry import cylinder_points, triangle_arrays
from .hulls import convex_hull

ON_SURFACE = 1e-9  # a ray starting this close outside or inside a face starts on it
AT_LIMIT = 1e-12   # entries this close below a limit count as at it (rounding)
_PARALLEL = 1e-15
PLANE_DIGITS = 12  # a hull's triangles whose planes agree to this many decimals are one face
_MESH_CHUNK = 200_000  # ray × triangle pairs worked on at once (bounded memory)


class Shape(Protocol):
    """A part's shape in its own frame, as rays meet it."""

    centre: np.ndarray  # of a sphere around the shape
    radius: float

    def entries(self, origins: np.ndarray, directions: np.ndarray,
                limits: Sequence[float]) -> np.ndarray:
        """(rays, limits): the first front-face entry at or beyond each limit, or inf."""


def _from_one_entry(enter: np.ndarray, valid: np.ndarray, limits: Sequence[float]) -> np.ndarray:
    """Per limit, for shapes a ray enters at most once (convex ones)."""
    enter = np.where(valid, np.maximum(enter, 0.0), np.inf)[:, None]
    low, reached = _lows(tuple(limits))
    return np.where(enter >= reached, np.maximum(enter, low), np.inf)


@lru_cache(maxsize=64)
def _lows(limits: tuple[float, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Limits as an array, and how far below each an entry still counts as at it: the
    same few limits every tick (sensing asks for two), made once each."""
    low = np.asarray(limits, dtype=float)
    reached = low - AT_LIMIT
    low.flags.writeable = reached.flags.writeable = False  # (shared by every call)
    return low, reached


class Sphere:
    """A sphere of ``radius`` centred at the origin."""

    def __init__(self, radius: float) -> None:
        self.radius, self.centre = float(radius), np.zeros(3)

    def entries(self, origins: np.ndarray, directions: np.ndarray,
                limits: Sequence[float]) -> np.ndarray:
        b = np.einsum("ij,ij->i", origins, directions)
        c = np.einsum("ij,ij->i", origins, origins) - self.radius ** 2
        reach = b * b - c
        enter = -b - np.sqrt(np.maximum(reach, 0.0))
        outside = c >= -ON_SURFACE * self.radius
        return _from_one_entry(enter, outside & (reach >= 0) & (enter >= -ON_SURFACE), limits)


class Convex:
    """A convex hull by its face planes n·p ≤ c (n of unit length)."""

    def __init__(self, normals: np.ndarray, offsets: np.ndarray, corners: np.ndarray) -> None:
        self.normals, self.offsets = normals, offsets
        self.centre = (corners.min(axis=0) + corners.max(axis=0)) / 2
        self.radius = float(np.linalg.norm(corners - self.centre, axis=1).max())

    def entries(self, origins: np.ndarray, directions: np.ndarray,
                limits: Sequence[float]) -> np.ndarray:
        rays = len(origins)
        return convex_entries(np.broadcast_to(self.normals, (rays, *self.normals.shape)),
                              np.broadcast_to(self.offsets, (rays, len(self.offsets))),
                              origins, directions, limits)


def convex_entries(normals: np.ndarray, offsets: np.ndarray, origins: np.ndarray,
                   directions: np.ndarray, limits: Sequence[float]) -> np.ndarray:
    """:meth:`Shape.entries` of many rays, each against convex planes of its own: ray k
    against n·p ≤ c for the rows of ``normals[k]`` (planes, 3) and ``offsets[k]``. Rows of
    zeros with a positive offset are no planes (they pad hulls with fewer faces)."""
    return convex_entries_of(normals, offsets, np.stack((directions, origins), axis=2), limits)


def convex_entries_of(normals: np.ndarray, offsets: np.ndarray, rays: np.ndarray,
                      limits: Sequence[float]) -> np.ndarray:
    """:func:`convex_entries` of rays given as one (rays, 3, 2) array: each ray's direction
    and origin side by side (as a batch of rays turned into their shapes' frames comes)."""
    # both products in one batched matmul (a third of two einsums' time at these sizes)
    products = normals @ rays  # (rays, planes, 2)
    towards = products[..., 0]
    gaps = offsets - products[..., 1]   # ≥ 0: inside that plane
    with np.errstate(divide="ignore", invalid="ignore"):
        at = gaps / towards
    entering = towards < -_PARALLEL
    # a plane the ray does not enter, with the origin outside it, leaves nothing to meet
    # (beside it, or past it already): as if entered at infinity, which meets nothing
    enter = np.where(entering, at, np.where(gaps < -ON_SURFACE, np.inf, -np.inf)).max(axis=1)
    leave = np.where(towards > _PARALLEL, at, np.inf).min(axis=1)
    return _from_one_entry(enter, (enter <= leave) & (enter >= -ON_SURFACE), limits)


class Ground:
    """The plane y = 0, met from above only (world frame)."""

    def entries(self, origins: np.ndarray, directions: np.ndarray,
                limits: Sequence[float]) -> np.ndarray:
        height, falling = origins[:, 1], -directions[:, 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            enter = height / falling
        return _from_one_entry(enter, (falling > 0) & (height >= -ON_SURFACE), limits)


GROUND_SHAPE = Ground()


def box(size: Sequence[float]) -> Convex:
    """A box of ``size`` centred at the origin."""
    half = np.asarray(size, dtype=float) / 2
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * half
    return Convex(np.vstack([np.eye(3), -np.eye(3)]), np.concatenate([half, half]), corners)


def hull(points: Sequence[Sequence[float]]) -> Convex:
    """The convex hull of ``points``, by its distinct face planes."""
    shape = convex_hull(points)
    corners, planes = shape.points, shape.equations  # n·p + d ≤ 0 inside
    # qhull gives a plane per triangle of a face (a box's side twice, a 1.0 finger's 28 for
    # its 10 faces): one of each is the same shape and every ray meets a third as many.
    # Planes that round apart stay apart, which only keeps a plane twice.
    _, first = np.unique(np.round(planes, PLANE_DIGITS), axis=0, return_index=True)
    planes = planes[np.sort(first)]
    return Convex(planes[:, :3], -planes[:, 3], corners)


class Triangles:
    """A mesh's triangles (counter-clockwise seen from outside)."""

    def __init__(self, vertices: np.ndarray, triangles: np.ndarray) -> None:
        a, b, c = (vertices[triangles[:, k]] for k in range(3))
        self.a, self.ab, self.ac = a, b - a, c - a
        self.normals = np.cross(self.ab, self.ac)  # outwards: faces turn counter-clockwise
        self.centre = (vertices.min(axis=0) + vertices.max(axis=0)) / 2
        self.radius = float(np.linalg.norm(vertices - self.centre, axis=1).max())

    def entries(self, origins: np.ndarray, directions: np.ndarray,
                limits: Sequence[float]) -> np.ndarray:
        step = max(1, _MESH_CHUNK // len(self.a))
        return np.concatenate([self._entries(origins[k:k + step], directions[k:k + step], limits)
                               for k in range(0, len(origins), step)])

    def _entries(self, origins: np.ndarray, directions: np.ndarray,
                 limits: Sequence[float]) -> np.ndarray:
        # Möller–Trumbore for every ray against every triangle: (rays, triangles) arrays
        d = directions[:, None, :]
        p = np.cross(d, self.ac)
        det = np.einsum("tj,rtj->rt", self.ab, p)
        s = origins[:, None, :] - self.a
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.einsum("rtj,rtj->rt", s, p) / det
            q = np.cross(s, self.ab)
            v = np.einsum("rtj,rj->rt", q, directions) / det
            t = np.einsum("tj,rtj->rt", self.ac, q) / det
            facing = directions @ self.normals.T < 0
            edge = 1e-12  # a ray along an edge shared by two faces meets one of them
            hit = facing & (u >= -edge) & (v >= -edge) & (u + v <= 1 + edge) & (t >= -ON_SURFACE)
        t = np.where(hit, np.maximum(t, 0.0), np.inf)
        return np.stack([np.where(t >= limit - AT_LIMIT, np.maximum(t, limit), np.inf).min(axis=1)
                         for limit in limits], axis=1)


def shape_of(geometry: dict[str, Any], assets: AssetLibrary) -> Shape:
    """The shape rays meet for a physical part's geometry."""
    kind = geometry["kind"]
    if kind == "sphere":
        return Sphere(geometry["radius"])
    if kind == "box":
        return box(geometry["size"])
    if kind == "convex":
        return hull(geometry["points"])
    if kind == "cylinder":
        return hull(cylinder_points(geometry))
    if kind == "triangles":
        return Triangles(*triangle_arrays(geometry))
    if kind == "mesh":  # the drawn triangles, not the envelope that contacts use
        mesh = assets.mesh(geometry["url"])
        return Triangles(*placed(geometry, mesh.vertices, mesh.triangles))
    raise ValueError(f"rays do not meet geometry kind {kind!r}")
