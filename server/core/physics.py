"""The collision world: a narrow interface over one PyBullet ``DIRECT`` client.

Kinematic mode, as in 1.0: bodies are placed from the transform tree and never stepped.
Bullet skips pairs of mass-0 bodies, so every part body has mass 1; since the world is
never stepped, nothing falls or gets pushed.
"""

from __future__ import annotations

import ctypes
import os
import sys
from typing import Any, Sequence


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

from .math3d import Pose, Vec3

GROUND = "ground"
_BODY_MASS = 1.0


class PhysicsWorld:
    """Collision bodies keyed by node id, plus the ground plane y = 0."""

    def __init__(self) -> None:
        self._client = pybullet.connect(pybullet.DIRECT)
        self._bodies: dict[str, int] = {}
        self._keys: dict[int, str] = {}
        plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, planeNormal=[0, 1, 0],
                                              physicsClientId=self._client)
        ground = pybullet.createMultiBody(0, plane, physicsClientId=self._client)
        self._keys[ground] = GROUND

    def close(self) -> None:
        """Release the PyBullet client."""
        if self._client is not None:
            pybullet.disconnect(physicsClientId=self._client)
            self._client = None

    def __contains__(self, key: str) -> bool:
        return key in self._bodies

    def __len__(self) -> int:
        return len(self._bodies)

    def add(self, key: str, geometry: dict[str, Any], pose: Pose) -> None:
        """A new body for ``key`` shaped by a part geometry (sphere, box or convex)."""
        shape = pybullet.createCollisionShape(physicsClientId=self._client,
                                              **_shape_arguments(geometry))
        body = pybullet.createMultiBody(_BODY_MASS, shape, basePosition=pose[0],
                                        baseOrientation=pose[1], physicsClientId=self._client)
        self._bodies[key] = body
        self._keys[body] = key

    def remove(self, key: str) -> None:
        """Take the body of ``key`` out of the world."""
        body = self._bodies.pop(key)
        del self._keys[body]
        pybullet.removeBody(body, physicsClientId=self._client)

    def move(self, key: str, pose: Pose) -> None:
        """Place the body of ``key`` at a world pose."""
        pybullet.resetBasePositionAndOrientation(self._bodies[key], pose[0], pose[1],
                                                 physicsClientId=self._client)

    def pose(self, key: str) -> Pose:
        """The world pose PyBullet holds for ``key``."""
        position, orientation = pybullet.getBasePositionAndOrientation(
            self._bodies[key], physicsClientId=self._client)
        return tuple(position), tuple(orientation)

    def cast_rays(self, starts: Sequence[Vec3], ends: Sequence[Vec3]) -> list[tuple[str, float]]:
        """For each ray, the key hit first and the hit fraction ('' and 1.0 for a miss)."""
        hits = pybullet.rayTestBatch(list(starts), list(ends), physicsClientId=self._client)
        return [(self._keys.get(hit[0], ""), hit[2]) for hit in hits]

    def overlaps(self) -> set[tuple[str, str]]:
        """Pairs of keys (sorted) whose shapes touch or intersect: closest distance ≤ 0."""
        pybullet.performCollisionDetection(physicsClientId=self._client)
        pairs = set()
        for point in pybullet.getContactPoints(physicsClientId=self._client):
            if point[8] <= 0.0:
                a, b = self._keys.get(point[1]), self._keys.get(point[2])
                if a and b and a != b:
                    pairs.add((a, b) if a < b else (b, a))
        return pairs


def _shape_arguments(geometry: dict[str, Any]) -> dict[str, Any]:
    kind = geometry["kind"]
    if kind == "sphere":
        return {"shapeType": pybullet.GEOM_SPHERE, "radius": geometry["radius"]}
    if kind == "box":
        return {"shapeType": pybullet.GEOM_BOX,
                "halfExtents": [s / 2 for s in geometry["size"]]}
    if kind == "convex":
        return {"shapeType": pybullet.GEOM_MESH, "vertices": geometry["points"]}
    raise ValueError(f"no collision shape for geometry kind {kind!r}")
