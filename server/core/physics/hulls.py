"""Convex hulls of any point set: flat, straight or single-point sets get a hair of depth.

An edged finger of zero thickness or a palm of zero width is still a shape the user
made; rays must meet it and contacts measure it. Qhull refuses point sets without volume,
so such a set is thickened by ``HAIR`` (relative to its size) across the directions in
which it has none: distances change by no more than that.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

HAIR = 1e-9


def convex_hull(points: Sequence[Sequence[float]] | np.ndarray) -> Any:
    """``scipy.spatial.ConvexHull`` of ``points``, thickened first where they are flat."""
    from scipy.spatial import ConvexHull

    return ConvexHull(solid(np.asarray(points, dtype=float)))


def solid(points: np.ndarray) -> np.ndarray:
    """``points``, or for a set without volume the set doubled a hair to either side."""
    centred = points - points.mean(axis=0)
    scale = max(float(np.abs(centred).max()), 1.0)
    _, sizes, axes = np.linalg.svd(centred, full_matrices=len(points) < 3)  # never n × n
    sizes = np.concatenate([sizes, np.zeros(3 - len(sizes))])
    for axis, size in zip(axes, sizes):
        if size <= 1e-7 * scale:
            points = np.vstack([points + HAIR * scale * axis, points - HAIR * scale * axis])
    return points
