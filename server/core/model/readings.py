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

from ..kit.math3d import Pose, Vec3
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
                 pose_of: Callable[[Node], Pose] | None = None) -> dict[str, Reading]:
    """Readings of ``sensors`` (shapes already placed); ``contacts_of(sensor)`` lists ids,
    ``pose_of(sensor)`` gives its world pose (by default the tree's)."""
    if not sensors:
        return {}
    poses = [sensor.world_pose() if pose_of is None else pose_of(sensor) for sensor in sensors]
    origins = np.array([position for position, _ in poses], dtype=float)
    # each sensor's +Y axis in the world: the second column of its rotation matrix
    directions = np.array([(2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x))
                           for _, (x, y, z, w) in poses])
    _, hits = targets.cast(origins, directions, (0.0, part_figures.SENSOR_NEAR), part_figures.SENSOR_RANGE)
    touches = np.maximum(0.0, 1.0 - hits[:, 0] / part_figures.TOUCH_RANGE)  # 0 for inf too
    return {sensor.id: Reading(distance, touch, pose[0], tuple(contacts_of(sensor)))
            for sensor, distance, touch, pose in zip(sensors, hits[:, 1].tolist(),
                                                     touches.tolist(), poses)}
