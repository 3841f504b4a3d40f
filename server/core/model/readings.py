"""Sensor readings: one exact ray per sensor, along its world +Y.

The ray is met as 1.0's raycaster met it (:mod:`server.core.physics.raycast`): front faces of the
ground and of physical parts only, so motors and sensors are transparent and a sensor
never sees a body it starts inside. Its first hit within [0, ``TOUCH_RANGE``] gives the
touch reading; its first hit at or beyond ``SENSOR_NEAR`` the distance (nearer hits are
the pad's own business).
"""

from __future__ import annotations

from itertools import repeat
from typing import TYPE_CHECKING, Any, NamedTuple, Sequence

import numpy as np

from ..kit.math3d import Vec3
from ..kit.numbers import wire_number
from ..physics.contact_forces import ContactForce
from . import part_figures

if TYPE_CHECKING:
    from .node import Node
    from ..physics.raycast import RayTargets


class Reading(NamedTuple):
    """What one sensor senses: the manual's six readings follow from the first four, and
    ``force`` is what presses on its part and ``contacts`` who presses how (dynamic mode).
    A named tuple: a tick makes one per watched sensor."""

    distance: float
    touch: float
    position: Vec3
    objects: tuple[str, ...]
    force: float = 0.0
    contacts: tuple[ContactForce, ...] = ()

    def wire(self) -> dict[str, Any]:
        """The reading as frames carry it."""
        return {"distance": wire_number(self.distance), "touch": self.touch,
                "position": list(self.position), "objects": list(self.objects),
                "force": self.force, "contacts": [force.wire() for force in self.contacts]}

    def force_from(self, other: str) -> float:
        """Newtons pressing on the part from ``other`` (a part's id or "ground")."""
        return next((force.normal for force in self.contacts if force.other == other), 0.0)


def read_sensors(targets: RayTargets, sensors: Sequence[Node], contacts: Sequence[Sequence[str]],
                 forces: Sequence[tuple[ContactForce, ...]] | None, origins: np.ndarray,
                 turns: np.ndarray) -> dict[str, Reading]:
    """Readings of ``sensors`` (shapes already placed), given what each one's part touches
    and what presses on it (None: nothing presses on any), and their world positions and
    rotation matrices (n×3 and n×3×3 arrays).
    A part something presses on touches it (1), whatever the pad's ray sees: a fingertip
    pressed on an object from the pad's side, or through the thin gap Bullet keeps between
    surfaces in contact."""
    if not sensors:
        return {}
    directions = turns[:, :, 1]  # each sensor's +Y axis in the world
    hits = targets.distances(origins, directions, (0.0, part_figures.SENSOR_NEAR), part_figures.SENSOR_RANGE)
    touches = np.maximum(0.0, 1.0 - hits[:, 0] / part_figures.TOUCH_RANGE)  # 0 for inf too
    pressed = repeat(()) if forces is None else forces
    return {sensor.id: Reading(distance, 1.0 if pressing else touch, tuple(position), tuple(touching),
                               sum(force.normal for force in pressing) if pressing else 0, pressing)
            for sensor, distance, touch, position, touching, pressing in zip(
                sensors, hits[:, 1].tolist(), touches.tolist(), origins.tolist(), contacts, pressed)}
