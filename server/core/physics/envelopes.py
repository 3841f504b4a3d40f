"""Collision envelopes of mesh parts: the mesh's convex hull, cut back at the joints.

Neighbouring meshes overlap at their joints by design (rounded ends sink into each other),
so a hull of the whole mesh would make every joint a contact. Each part therefore keeps
its envelope within a few half-spaces (:data:`Plane`): a finger's ends are cut into
pyramids (:func:`pyramid`) whose 45° faces let its neighbour bend up to 90° without
touching, a palm is cut flat below its fingers (:func:`half_space`). The result is
thinned to a few dozen points of its hull, which is what physics uses. A part too short
for its cuts keeps its whole hull; an envelope that cannot be made at all (qhull gives
up) refuses the part with ``bad_asset`` when it is created, never later in a tick.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Sequence

import numpy as np

from ..kit.errors import BadAsset
from ..kit.math3d import Vec3
from .assets import MeshFile
from .hulls import convex_hull, solid

ENVELOPE_POINTS = 64
PYRAMID_SIDES = 8  # faces of a joint's pyramid: its corners stand 47° off its axis

Plane = tuple[Vec3, float]


class NothingLeft(ValueError):
    """The cuts leave nothing of a hull (a part shorter than its joints' cuts)."""  # (n, c): the envelope keeps the points p with n·p ≤ c


def half_space(point: Vec3, normal: Vec3, gap: float) -> Plane:
    """Keep what lies at least ``gap`` behind the plane through ``point`` facing ``normal``."""
    n = _unit(normal)
    return tuple(n), float(n @ np.asarray(point) - gap)  # type: ignore[return-value]


def pyramid(apex: Vec3, axis: Vec3, gap: float,
            across: Sequence[Vec3] | None = None) -> list[Plane]:
    """Keep a pyramid opening along ``axis`` from ``gap`` beyond ``apex``, faces at 45°.

    ``across`` are the directions its faces lean towards (default: eight around the
    axis); give two opposite ones for a joint that bends in one plane only.
    """
    a, q = _unit(axis), np.asarray(apex, dtype=float)
    planes = []
    for side in across if across is not None else _around(a):
        normal = _unit(side) - a  # (p - q)·a ≥ gap + (p - q)·e, rearranged to n·p ≤ c
        planes.append((tuple(float(c) for c in normal), float(normal @ q - gap)))
    return planes  # type: ignore[return-value]


def _around(axis: np.ndarray) -> list[np.ndarray]:
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    first = _unit(np.cross(axis, helper))
    second = np.cross(axis, first)
    angles = [2 * math.pi * k / PYRAMID_SIDES for k in range(PYRAMID_SIDES)]
    return [math.cos(t) * first + math.sin(t) * second for t in angles]


def _unit(v: Sequence[float]) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def envelope(mesh: MeshFile, offset: Vec3, mirror: bool, cuts: Sequence[Plane] = (),
             count: int = ENVELOPE_POINTS) -> tuple[Vec3, ...]:
    """About ``count`` points of the hull of the mesh (moved by ``offset``, mirrored in X
    when ``mirror``) within the ``cuts``, in the part's frame.

    The points are spread over the hull (farthest-point order from the topmost one), so
    the envelope follows the mesh closely with far fewer points than the hull has.
    """
    try:
        if not mirror:
            return _envelope(mesh, tuple(offset), tuple(cuts), count)
        # the left-hand envelope mirrored: exactly the mirror image of the left part's
        flip = [(_mirrored(n), c) for n, c in cuts]
        return tuple(_mirrored(p) for p in _envelope(mesh, _mirrored(offset), tuple(flip), count))
    except Exception as error:  # qhull's own errors, or cuts that leave nothing
        raise BadAsset(f"no collision envelope can be made of {mesh.url} placed so: "
                       f"{str(error).splitlines()[0][:160]}") from None


def hull_envelope(points: np.ndarray, count: int = ENVELOPE_POINTS) -> tuple[Vec3, ...]:
    """About ``count`` points of the convex hull of ``points`` (an imported link's
    collision elements), chosen as a mesh part's envelope is."""
    try:
        outline = convex_hull(points)
    except Exception as error:  # qhull's own errors
        raise BadAsset(f"no collision envelope can be made of these points: "
                       f"{str(error).splitlines()[0][:160]}") from None
    corners = outline.points[outline.vertices]
    return tuple(tuple(float(c) for c in p) for p in _thinned(corners, count))


def _mirrored(v: Vec3) -> Vec3:
    return (-v[0], v[1], v[2])


@lru_cache(maxsize=256)
def _envelope(mesh: MeshFile, offset: Vec3, cuts: tuple[Plane, ...], count: int) -> tuple[Vec3, ...]:
    corners, planes = _mesh_hull(mesh)
    shift = np.array(offset)
    planes = np.hstack([planes[:, :3], planes[:, 3:] - planes[:, :3] @ shift[:, None]])
    try:
        corners = _cut(corners + shift, planes, cuts)
    except NothingLeft:  # a part too short for its joints' cuts: its whole hull, touching
        corners = corners + shift
    outline = convex_hull(corners)
    corners = outline.points[outline.vertices]
    return tuple(tuple(float(c) for c in p) for p in _thinned(corners, count))


def _thinned(corners: np.ndarray, count: int) -> np.ndarray:
    """About ``count`` of the hull's ``corners`` whose hull is closest to theirs.

    Greedy: start from the extremes along each axis, then keep adding the corner farthest
    outside the hull of those chosen. A reflection (in X, Y or Z about the centre) that
    maps the corners onto themselves maps the choice onto itself too: mirror-image parts
    get mirror-image envelopes.
    """
    from scipy.spatial import ConvexHull

    centre = (corners.max(axis=0) + corners.min(axis=0)) / 2
    mirrors = [np.where(np.arange(3) == axis, 2 * centre - corners, corners) for axis in range(3)]
    images = [image for image in mirrors if _maps_onto(image, corners)]
    chosen: set[int] = set()

    def choose(index: int) -> list[int]:  # with its images under every symmetry, and theirs
        added, new = [], [index]
        while new:
            chosen.update(new)
            added += new
            new = list(dict.fromkeys(k for i in new for image in images
                                     if (k := _nearest(corners, image[i])) not in chosen))
        return added

    for axis in range(3):
        choose(int(np.argmin(corners[:, axis])))
        choose(int(np.argmax(corners[:, axis])))
    hull = ConvexHull(solid(corners[sorted(chosen)]), incremental=True)
    while len(chosen) < min(count, len(corners)):
        planes = hull.equations
        outside = (corners @ planes[:, :3].T + planes[:, 3]).max(axis=1)
        farthest = int(np.argmax(outside))
        if outside[farthest] <= 1e-12:
            break
        try:
            hull.add_points(corners[choose(farthest)])
        except Exception:  # qhull gives up on a near-flat facet: start this hull afresh
            hull.close()
            hull = ConvexHull(solid(corners[sorted(chosen)]), incremental=True)
    hull.close()
    return corners[sorted(chosen)]


def _maps_onto(image: np.ndarray, corners: np.ndarray) -> bool:
    from scipy.spatial import cKDTree

    distances, _ = cKDTree(corners).query(image)
    return bool(distances.max() < 1e-9)


def _nearest(corners: np.ndarray, point: np.ndarray) -> int:
    return int(np.argmin(np.linalg.norm(corners - point, axis=1)))


@lru_cache(maxsize=64)
def _mesh_hull(mesh: MeshFile) -> tuple[np.ndarray, np.ndarray]:
    """The corners and face planes (n·p + d ≤ 0 inside) of a mesh's hull, file frame."""
    outline = convex_hull(mesh.vertices)
    return outline.points[outline.vertices], outline.equations


def _cut(corners: np.ndarray, planes: np.ndarray, cuts: tuple[Plane, ...]) -> np.ndarray:
    """The corners of the hull (``corners``, its ``planes``) within the cuts' half-spaces."""
    if not cuts:
        return corners
    from scipy.spatial import HalfspaceIntersection

    halfspaces = np.vstack([planes, [[*n, -c] for n, c in cuts]])
    return HalfspaceIntersection(halfspaces, _inside(corners, halfspaces, len(cuts))).intersections


def _inside(corners: np.ndarray, halfspaces: np.ndarray, cuts: int) -> np.ndarray:
    """A point strictly inside every half-space: the mean of the corners the last ``cuts``
    half-spaces keep (all are in the others), else the point deepest inside (slower)."""
    extra = halfspaces[-cuts:]
    kept = corners[(corners @ extra[:, :3].T + extra[:, 3] <= 0).all(axis=1)]
    if len(kept) >= 4:
        mean = kept.mean(axis=0)
        if (halfspaces[:, :3] @ mean + halfspaces[:, 3] < -1e-9).all():
            return mean
    from scipy.optimize import linprog

    norms = np.linalg.norm(halfspaces[:, :3], axis=1, keepdims=True)
    deepest = linprog([0, 0, 0, -1], A_ub=np.hstack([halfspaces[:, :3], norms]),
                      b_ub=-halfspaces[:, 3], bounds=[(None, None)] * 3 + [(0, None)])
    if not deepest.success or deepest.x[3] <= 1e-9:
        raise NothingLeft("the cuts leave nothing of the mesh's hull")
    return deepest.x[:3]
