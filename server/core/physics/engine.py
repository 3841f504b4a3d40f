"""The collision world: a narrow interface over one PyBullet ``DIRECT`` client.

Kinematic mode, as in 1.0: bodies are placed from the transform tree and never stepped,
so nothing falls or gets pushed. Part bodies have mass 1 (Bullet keeps the world boxes of
moved non-static bodies current). Rays are not Bullet's: see :mod:`server.core.physics.raycast`.

Contacts are those of the exact shapes: a pair is measured with ``getClosestPoints``
(never through Bullet's contact manifolds, which keep points from earlier poses after a
body is teleported, and whose pair cache grows with the square of overlapping bodies),
and the collision margin that pads convex hulls (``CONVEX_MARGIN``) is subtracted again.
Which pairs to measure is decided by :mod:`server.core.physics.contacts`.
"""

from __future__ import annotations

import ctypes
import os
import sys
from typing import Any


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

from ..kit.math3d import Pose, Vec3
from .geometry import solid_points
from .hulls import HAIR

ENGINE = "pybullet"  # the one physics engine (the viewer's engine= option must name it)
GROUND = "ground"
_BODY_MASS = 1.0
CONVEX_MARGIN = 0.001  # PyBullet pads every convex mesh shape by this much
TOUCH_TOLERANCE = 1e-9  # shapes this close count as touching (rounding, not geometry)
# Bodies are in group 2 and collide with group 1 only: Bullet's broadphase then never
# pairs two bodies (no pair cache, no manifolds, whatever overlaps). Contacts are tested
# pair by pair instead.
_BODY_GROUP, _BODY_MASK = 2, 1
# PyBullet keeps about 1 kB for every body ever removed and never frees a shape; a fresh
# client after this many removals gives the memory back.
REBUILD_AFTER_REMOVALS = 10_000


class PhysicsWorld:
    """Collision bodies keyed by node id, plus the ground plane y = 0.

    Bodies of equal geometry share one collision shape.
    """

    def __init__(self) -> None:
        self._client: int | None = None
        self._bodies: dict[str, int] = {}
        self._placed: dict[str, tuple[dict[str, Any], Pose]] = {}
        self.removals = 0
        self.rebuilds = 0
        self._connect()

    def _connect(self) -> None:
        self._client = pybullet.connect(pybullet.DIRECT)
        self._keys: dict[int, str] = {}
        self._padding: dict[int, float] = {}
        self._shapes: dict[tuple, int] = {}
        plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, planeNormal=[0, 1, 0],
                                              physicsClientId=self._client)
        self._ground = pybullet.createMultiBody(0, plane, physicsClientId=self._client)
        self._filter(self._ground)
        self._keys[self._ground] = GROUND
        self._padding[self._ground] = 0.0

    def _filter(self, body: int) -> None:
        pybullet.setCollisionFilterGroupMask(body, -1, _BODY_GROUP, _BODY_MASK,
                                             physicsClientId=self._client)

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
        body = pybullet.createMultiBody(_BODY_MASS, self._shape(geometry), basePosition=pose[0],
                                        baseOrientation=pose[1], physicsClientId=self._client)
        self._filter(body)
        self._bodies[key] = body
        self._keys[body] = key
        self._padding[body] = 0.0 if geometry["kind"] in ("sphere", "box") else CONVEX_MARGIN
        self._placed[key] = (geometry, pose)

    def _shape(self, geometry: dict[str, Any]) -> int:
        arguments = shape_arguments(geometry)
        key = tuple((name, tuple(map(tuple, v)) if name == "vertices" else
                     tuple(v) if isinstance(v, list) else v) for name, v in arguments.items())
        shape = self._shapes.get(key)
        if shape is None:
            shape = self._shapes[key] = pybullet.createCollisionShape(
                physicsClientId=self._client, **arguments)
        return shape

    def remove(self, key: str) -> None:
        """Take the body of ``key`` out of the world."""
        body = self._bodies.pop(key)
        del self._keys[body], self._padding[body], self._placed[key]
        pybullet.removeBody(body, physicsClientId=self._client)
        self.removals += 1

    def move(self, key: str, pose: Pose) -> None:
        """Place the body of ``key`` at a world pose."""
        self.move_many([key], [pose])

    def move_many(self, keys: list[str], poses: list[Pose]) -> None:
        """Place the bodies of ``keys`` at their world poses."""
        reset, client = pybullet.resetBasePositionAndOrientation, self._client
        bodies, placed = self._bodies, self._placed
        for key, pose in zip(keys, poses):
            reset(bodies[key], pose[0], pose[1], physicsClientId=client)
            placed[key] = (placed[key][0], pose)

    def needs_rebuild(self) -> bool:
        """True when enough bodies were removed that a fresh client would free memory."""
        return self.removals >= REBUILD_AFTER_REMOVALS or \
            len(self._shapes) > 2 * len(self._bodies) + REBUILD_AFTER_REMOVALS // 10

    def rebuild(self) -> None:
        """Move every body into a fresh PyBullet client and release the old one."""
        placed = self._placed
        self.close()
        self._bodies, self._placed = {}, {}
        self._connect()
        for key, (geometry, pose) in placed.items():
            self.add(key, geometry, pose)
        self.removals = 0
        self.rebuilds += 1

    def pose(self, key: str) -> Pose:
        """The world pose PyBullet holds for ``key``."""
        position, orientation = pybullet.getBasePositionAndOrientation(
            self._bodies[key], physicsClientId=self._client)
        return tuple(position), tuple(orientation)

    def aabb(self, key: str) -> tuple[Vec3, Vec3]:
        """The world box around the body of ``key`` (its shape's margin included)."""
        low, high = pybullet.getAABB(self._bodies[key], physicsClientId=self._client)
        return tuple(low), tuple(high)

    def aabbs(self, keys: list[str]) -> list[tuple[Vec3, Vec3]]:
        """The world boxes of the bodies of ``keys`` (as :meth:`aabb`), in order."""
        get, bodies, client = pybullet.getAABB, self._bodies, self._client
        return [get(bodies[key], physicsClientId=client) for key in keys]

    def touching(self, key_a: str, key_b: str) -> bool:
        """True when the exact shapes of two bodies (or a body and the ground) touch.

        Convex shapes are padded by ``CONVEX_MARGIN``, which the distance is measured against.
        """
        return self.touching_many(key_a, [key_b])[0]

    def touching_many(self, key: str, others: list[str]) -> list[bool]:
        """For each of ``others``: does it touch ``key`` (as :meth:`touching`)?"""
        closest, client, padding = pybullet.getClosestPoints, self._client, self._padding
        bodies, ground, tolerance = self._bodies, self._ground, TOUCH_TOLERANCE
        a = ground if key == GROUND else bodies[key]
        out = []
        for other in others:
            b = ground if other == GROUND else bodies[other]
            reach = tolerance - padding[a] - padding[b]
            out.append(any(point[8] <= reach
                           for point in closest(a, b, tolerance, physicsClientId=client)))
        return out


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
