"""PyBullet, imported without its banner, and the collision shapes of part geometries."""

from __future__ import annotations

import ctypes
import os
import sys
from typing import Any

from .geometry import solid_points
from .hulls import HAIR

def _quiet_import():  # type: ignore[no-untyped-def]
    # PyBullet prints its build time when imported; the server's output belongs to its log.
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(fd) for fd in (1, 2)]
    devnull = os.open(os.devnull, os.O_WRONLY)
    for fd in (1, 2):
        os.dup2(devnull, fd)
    try:
        import pybullet
        ctypes.CDLL(None).fflush(None)  # the C library buffers it; flush while muted
    finally:
        for fd, copy in zip((1, 2), saved):
            os.dup2(copy, fd)
            os.close(copy)
        os.close(devnull)
    return pybullet


pybullet = _quiet_import()


def shape_arguments(geometry: dict[str, Any]) -> dict[str, Any]:
    """``createCollisionShape`` arguments for a part geometry (the bench's floor uses them too)."""
    kind = geometry["kind"]
    if kind == "sphere":  # Bullet refuses a sphere of radius 0: a point gets a hair's
        return {"shapeType": pybullet.GEOM_SPHERE, "radius": max(geometry["radius"], HAIR)}
    if kind == "box":
        return {"shapeType": pybullet.GEOM_BOX,
                "halfExtents": [s / 2 for s in geometry["size"]]}
    if kind in ("convex", "mesh"):  # a mesh part's envelope: its hull's points
        return {"shapeType": pybullet.GEOM_MESH, "vertices": geometry["points"]}
    if kind in ("cylinder", "triangles"):  # contacts measure a triangle mesh by its hull
        return {"shapeType": pybullet.GEOM_MESH, "vertices": solid_points(geometry)}
    raise ValueError(f"no collision shape for geometry kind {kind!r}")
