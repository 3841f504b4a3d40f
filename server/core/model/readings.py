"""Sensor readings: one exact ray per sensor, along its world +Y.

The ray is met as 1.0's raycaster met it (:mod:`server.core.physics.raycast`): front faces of the
ground and of physical parts only, so motors and sensors are transparent and a sensor
never sees a body it starts inside. Its first hit within [0, ``TOUCH_RANGE``] gives the
touch reading; its first hit at or beyond ``SENSOR_NEAR`` the distance (nearer hits are
the pad's own business).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Sequence

import numpy as np

from ..kit.math3d import Vec3
from ..kit.numbers import wire_number
from . import part_figures

if TYPE_CHECKING:
    from .node import Node
    from ..physics.raycast import RayTargets


@dataclass(frozen=True)
class Reading:
    """What one sensor senses: the manual's six readings follow from these four."""

    distance: float
    touch: float
    position: Vec3
    objects: tuple[str, ...]

    def wire(self) -> dict[str, Any]:
        """The reading as frames carry it."""
        return {"distance": wire_number(self.distance), "touch": self.touch,
                "position": list(self.position), "objects": list(self.objects)}


def read_sensors(targets: RayTargets, sensors: Sequence[Node],
                 contacts_of: Callable[[Node], list[str]],
                 poses_of: Callable[[list[Node]], tuple[np.ndarray, np.ndarray]] | None = None
                 ) -> dict[str, Reading]:
    """Readings of ``sensors`` (shapes already placed); ``contacts_of(sensor)`` lists ids,
    ``poses_of(sensors)`` gives their world positions and quaternions as n×3 and n×4
    arrays (by default the tree's poses)."""
    if not sensors:
        return {}
    sensors = list(sensors)
    if poses_of is None:
        poses = [sensor.world_pose() for sensor in sensors]
        origins, quats = np.array([p for p, _ in poses]), np.array([q for _, q in poses])
    else:
        origins, quats = poses_of(sensors)
    # each sensor's +Y axis in the world: the second column of its rotation matrix
    x, y, z, w = quats.T
    directions = np.stack((2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)), axis=1)
    _, hits = targets.cast(origins, directions, (0.0, part_figures.SENSOR_NEAR), part_figures.SENSOR_RANGE)
    touches = np.maximum(0.0, 1.0 - hits[:, 0] / part_figures.TOUCH_RANGE)  # 0 for inf too
    return {sensor.id: Reading(distance, touch, tuple(position), tuple(contacts_of(sensor)))
            for sensor, distance, touch, position in zip(sensors, hits[:, 1].tolist(),
                                                         touches.tolist(), origins.tolist())}
