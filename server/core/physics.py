"""The collision world: a narrow interface over one PyBullet ``DIRECT`` client.

Kinematic mode, as in 1.0: bodies are placed from the transform tree and never stepped.
Bullet skips pairs of mass-0 bodies, so every part body has mass 1; since the world is
never stepped, nothing falls or gets pushed.

Two Bullet habits are undone here so that contacts are those of the exact shapes:
convex hulls are padded by a collision margin (``CONVEX_MARGIN``, subtracted again), and
contact manifolds keep points from earlier poses after a body is teleported (so a pair
that looks touching is measured afresh with ``getClosestPoints``).
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

ENGINE = "pybullet"  # the one physics engine (the viewer's engine= option must name it)
GROUND = "ground"
_BODY_MASS = 1.0
CONVEX_MARGIN = 0.001  # PyBullet pads every convex mesh shape by this much
TOUCH_TOLERANCE = 1e-9  # shapes this close count as touching (rounding, not geometry)
_THREADED_RAYS = 256


class PhysicsWorld:
    """Collision bodies keyed by node id, plus the ground plane y = 0."""

    def __init__(self) -> None:
        self._client = pybullet.connect(pybullet.DIRECT)
        self._bodies: dict[str, int] = {}
        self._keys: dict[int, str] = {}
        self._padding: dict[int, float] = {}
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
        self._padding[body] = CONVEX_MARGIN if geometry["kind"] == "convex" else 0.0

    def remove(self, key: str) -> None:
        """Take the body of ``key`` out of the world."""
        body = self._bodies.pop(key)
        del self._keys[body], self._padding[body]
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
        """For each ray, the key hit first and the hit fraction ('' and 1.0 for a miss).

        Large batches use every core (PyBullet's ``numThreads=0``); small ones stay on
        this thread, where starting threads would cost more than it saves.
        """
        threads = 0 if len(starts) >= _THREADED_RAYS else -1
        hits = pybullet.rayTestBatch(list(starts), list(ends), numThreads=threads,
                                     physicsClientId=self._client)
        return [(self._keys.get(hit[0], ""), hit[2]) for hit in hits]

    def overlaps(self) -> set[tuple[str, str]]:
        """Pairs of keys (sorted) whose exact shapes touch or intersect."""
        client = self._client
        pybullet.performCollisionDetection(physicsClientId=client)
        nearest: dict[tuple[int, int], float] = {}
        for point in pybullet.getContactPoints(physicsClientId=client):
            pair = (point[1], point[2])
            nearest[pair] = min(point[8], nearest.get(pair, point[8]))
        pairs = set()
        for (a, b), distance in nearest.items():
            padding = self._padding.get(a, 0.0) + self._padding.get(b, 0.0)
            if distance <= TOUCH_TOLERANCE - padding and self._touch(a, b, padding):
                key_a, key_b = self._keys.get(a), self._keys.get(b)
                if key_a and key_b and key_a != key_b:
                    pairs.add((key_a, key_b) if key_a < key_b else (key_b, key_a))
        return pairs

    def _touch(self, a: int, b: int, padding: float) -> bool:
        """A fresh measure of a pair that looks touching (manifolds can hold stale points)."""
        points = pybullet.getClosestPoints(a, b, TOUCH_TOLERANCE, physicsClientId=self._client)
        return any(point[8] <= TOUCH_TOLERANCE - padding for point in points)


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
