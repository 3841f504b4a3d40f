"""Collision envelopes of mesh parts: the mesh's convex hull, cut back at the joints.

Neighbouring meshes overlap at their joints by design (rounded ends sink into each other),
so a hull of the whole mesh would make every joint a contact. Each part therefore keeps
its envelope within a few half-spaces (:data:`Plane`): a finger's ends are cut into
pyramids (:func:`pyramid`) whose 45° faces let its neighbour bend up to 90° without
touching, a palm is cut flat below its fingers (:func:`half_space`). The result is
thinned to a few dozen points of its hull, which is what physics uses.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Sequence

import numpy as np

from .assets import Mesh
from .hulls import convex_hull
from .math3d import Vec3

ENVELOPE_POINTS = 64
PYRAMID_SIDES = 8  # faces of a joint's pyramid: its corners stand 47° off its axis

Plane = tuple[Vec3, float]  # (n, c): the envelope keeps the points p with n·p ≤ c


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


def envelope(mesh: Mesh, offset: Vec3, mirror: bool, cuts: Sequence[Plane] = (),
             count: int = ENVELOPE_POINTS) -> tuple[Vec3, ...]:
    """About ``count`` points of the hull of the mesh (moved by ``offset``, mirrored in X
    when ``mirror``) within the ``cuts``, in the part's frame.

    The points are spread over the hull (farthest-point order from the topmost one), so
    the envelope follows the mesh closely with far fewer points than the hull has.
    """
    if not mirror:
        return _envelope(mesh, tuple(offset), tuple(cuts), count)
    # the left-hand envelope mirrored: exactly the mirror image of the left part's
    flip = [(_mirrored(n), c) for n, c in cuts]
    return tuple(_mirrored(p) for p in _envelope(mesh, _mirrored(offset), tuple(flip), count))


def _mirrored(v: Vec3) -> Vec3:
    return (-v[0], v[1], v[2])


@lru_cache(maxsize=256)
def _envelope(mesh: Mesh, offset: Vec3, cuts: tuple[Plane, ...], count: int) -> tuple[Vec3, ...]:
    placed = mesh.vertices + np.array(offset)
    outline = convex_hull(placed)
    corners = _cut(outline.points[outline.vertices], cuts)
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
    centre = (corners.max(axis=0) + corners.min(axis=0)) / 2
    images = [np.where(np.arange(3) == axis, 2 * centre - corners, corners)
              for axis in range(3) if _maps_onto(np.where(np.arange(3) == axis,
                                                          2 * centre - corners, corners), corners)]
    chosen: set[int] = set()

    def choose(index: int) -> None:  # with its images under every symmetry, and theirs
        new = [index]
        while new:
            chosen.update(new)
            new = [k for i in new for image in images
                   if (k := _nearest(corners, image[i])) not in chosen]

    for axis in range(3):
        choose(int(np.argmin(corners[:, axis])))
        choose(int(np.argmax(corners[:, axis])))
    while len(chosen) < min(count, len(corners)):
        planes = convex_hull(corners[sorted(chosen)]).equations
        outside = (corners @ planes[:, :3].T + planes[:, 3]).max(axis=1)
        farthest = int(np.argmax(outside))
        if outside[farthest] <= 1e-12:
            break
        choose(farthest)
    return corners[sorted(chosen)]


def _maps_onto(image: np.ndarray, corners: np.ndarray) -> bool:
    return all(np.linalg.norm(corners - p, axis=1).min() < 1e-9 for p in image)


def _nearest(corners: np.ndarray, point: np.ndarray) -> int:
    return int(np.argmin(np.linalg.norm(corners - point, axis=1)))


def _cut(points: np.ndarray, cuts: tuple[Plane, ...]) -> np.ndarray:
    """The corners of the hull of ``points`` intersected with the cuts' half-spaces."""
    if not cuts:
        return points
    from scipy.optimize import linprog
    from scipy.spatial import HalfspaceIntersection

    hull = convex_hull(points).equations  # rows (n, d): n·p + d ≤ 0 inside
    extra = np.array([[*n, -c] for n, c in cuts], dtype=float)
    halfspaces = np.vstack([hull, extra])
    # a point deepest inside all of them (Chebyshev centre) seeds the intersection
    norms = np.linalg.norm(halfspaces[:, :3], axis=1, keepdims=True)
    deepest = linprog([0, 0, 0, -1], A_ub=np.hstack([halfspaces[:, :3], norms]),
                      b_ub=-halfspaces[:, 3], bounds=[(None, None)] * 3 + [(0, None)])
    if not deepest.success or deepest.x[3] <= 1e-9:
        raise ValueError("the cuts leave nothing of the mesh's hull")
    return HalfspaceIntersection(halfspaces, deepest.x[:3]).intersections
