"""The references: bare PyBullet doing the same work as the server, with no server around it.

:class:`BareWorld` holds one body per physical part, of the same collision shape, in a
plain PyBullet world where every body may collide with every other (Bullet's own
broadphase and narrowphase). Its :meth:`~BareWorld.step` is the floor of a tick: place every
body at the pose the server computed, detect collisions, read the contact points.
:meth:`~BareWorld.rays` is the floor of sensing: the same rays in one ``rayTestBatch``.
"""

from __future__ import annotations

from typing import Any, Sequence

from server.core.kit.math3d import Pose
from server.core.physics.bullet import pybullet, shape_arguments


class BareWorld:
    """Bodies of the given geometries, at their first poses, and the ground plane."""

    def __init__(self, geometries: Sequence[dict[str, Any]], poses: Sequence[Pose]) -> None:
        self.client = pybullet.connect(pybullet.DIRECT)
        shapes: dict[str, int] = {}
        self.bodies = []
        for geometry, (position, orientation) in zip(geometries, poses):
            arguments = shape_arguments(geometry)
            key = repr(sorted(arguments.items()))
            if key not in shapes:
                shapes[key] = pybullet.createCollisionShape(physicsClientId=self.client,
                                                            **arguments)
            self.bodies.append(pybullet.createMultiBody(
                1.0, shapes[key], basePosition=position, baseOrientation=orientation,
                physicsClientId=self.client))
        plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, planeNormal=[0, 1, 0],
                                              physicsClientId=self.client)
        pybullet.createMultiBody(0, plane, physicsClientId=self.client)

    def step(self, poses: Sequence[Pose]) -> int:
        """Place every body, detect, read the contacts; the number of contact points."""
        reset, client = pybullet.resetBasePositionAndOrientation, self.client
        for body, (position, orientation) in zip(self.bodies, poses):
            reset(body, position, orientation, physicsClientId=client)
        pybullet.performCollisionDetection(physicsClientId=client)
        return len(pybullet.getContactPoints(physicsClientId=client))

    def rays(self, origins: Sequence[Sequence[float]], ends: Sequence[Sequence[float]]) -> int:
        """Cast rays in one batch; how many met something."""
        hits = pybullet.rayTestBatch(origins, ends, physicsClientId=self.client)
        return sum(1 for hit in hits if hit[0] >= 0)

    def close(self) -> None:
        """Release the PyBullet client."""
        pybullet.disconnect(physicsClientId=self.client)
