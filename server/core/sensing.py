"""Sensor readings: many sensors, one batched ray test.

Each sensor casts two rays along its world +Y: the distance ray from ``SENSOR_NEAR`` out
to ``SENSOR_RANGE`` and the touch ray over the pad, [0, ``TOUCH_RANGE``]. Only collision
bodies are hit (the ground and physical parts), so motors and sensors are transparent,
and a ray that starts inside a body does not see that body (as 1.0's raycaster did not).
Both rays start a hair early (``_EARLY``), because Bullet does not see a surface a ray
starts on: a sensor lying on the ground must read touch 1, one 0.05 above it 0.05.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Sequence

from . import figures
from .math3d import Vec3
from .wire import wire_number

if TYPE_CHECKING:
    from .physics import PhysicsWorld
    from .sensor import Sensor

_EARLY = 1e-6


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


def _rays(sensors: Sequence[Sensor]) -> tuple[list[Vec3], list[Vec3], list[Vec3]]:
    """Per sensor its position, and the two rays' starts and ends, distance ray first."""
    positions, starts, ends = [], [], []
    near, far, touch = figures.SENSOR_NEAR - _EARLY, figures.SENSOR_RANGE, figures.TOUCH_RANGE
    for sensor in sensors:
        (px, py, pz), (x, y, z, w) = sensor.world_pose()
        # the sensor's +Y axis in the world: the second column of its rotation matrix
        dx, dy, dz = 2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)
        positions.append((px, py, pz))
        starts += [(px + dx * near, py + dy * near, pz + dz * near),
                   (px - dx * _EARLY, py - dy * _EARLY, pz - dz * _EARLY)]
        ends += [(px + dx * far, py + dy * far, pz + dz * far),
                 (px + dx * touch, py + dy * touch, pz + dz * touch)]
    return positions, starts, ends


def read_sensors(physics: PhysicsWorld, sensors: Sequence[Sensor],
                 contacts_of: Callable[[Sensor], list[str]]) -> dict[str, Reading]:
    """Readings of ``sensors`` (bodies already placed); ``contacts_of(sensor)`` lists ids."""
    if not sensors:
        return {}
    positions, starts, ends = _rays(sensors)
    hits = physics.cast_rays(starts, ends)
    span = figures.SENSOR_RANGE - figures.SENSOR_NEAR + _EARLY
    readings = {}
    for k, sensor in enumerate(sensors):
        (far_key, far_fraction), (near_key, near_fraction) = hits[2 * k], hits[2 * k + 1]
        distance = _distance(far_fraction, span) if far_key else math.inf
        touch = _touch(near_fraction) if near_key else 0.0
        readings[sensor.id] = Reading(distance, touch, positions[k],
                                      tuple(contacts_of(sensor)))
    return readings


def _distance(fraction: float, span: float) -> float:
    """The distance of a hit at ``fraction`` of the distance ray (never below the pad)."""
    return max(figures.SENSOR_NEAR, figures.SENSOR_NEAR - _EARLY + fraction * span)


def _touch(fraction: float) -> float:
    """1 - d/TOUCH_RANGE for a hit at ``fraction`` of the touch ray."""
    distance = fraction * (figures.TOUCH_RANGE + _EARLY) - _EARLY
    return min(1.0, max(0.0, 1.0 - distance / figures.TOUCH_RANGE))
