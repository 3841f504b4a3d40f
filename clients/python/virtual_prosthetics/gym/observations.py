"""The environments' observation: one float32 vector, its parts in a fixed order
(:data:`PARTS`; :meth:`ObservationLayout.split` names them again).

Everything is in the palm's frame and SI at the hand's size: what a controller on the
hand would sense (its motors, its digits' forces on the object) and what a camera on the
wrist would see (the object and the target relative to the palm)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from gymnasium import spaces

from ..tasks.observation import Observation, conjugate, product, rotate
from ..tasks.trial import Trial

Vec = Sequence[float]


def parts(motors: int, digits: int) -> list[tuple[str, int]]:
    """The vector's parts and their lengths, in order."""
    return [("time", 1),                 # seconds since the episode began
            ("angles", motors),          # each motor's angle (rad; a slider's m)
            ("speeds", motors),          # each motor's speed (rad/s)
            ("efforts", motors),         # the torque each drove with in the last step (N·m)
            ("digitForces", digits),     # each digit's normal force on the object (N)
            ("objectPosition", 3),       # the object's centre from the palm's (m)
            ("objectQuaternion", 4),     # its turn from the palm's (x, y, z, w)
            ("objectVelocity", 3),       # how fast it moves relative to the palm (m/s)
            ("objectSpin", 3),           # how fast it turns relative to the palm (rad/s)
            ("targetPosition", 3),       # where it should be, from the palm (m)
            ("targetQuaternion", 4)]     # how it should be turned, from the palm's turn


@dataclass(frozen=True)
class ObservationLayout:
    """The observation of a hand of ``motors`` motors and ``digits`` digits."""

    motors: int
    digits: int

    @property
    def size(self) -> int:
        return sum(length for _, length in parts(self.motors, self.digits))

    def space(self) -> spaces.Box:
        """Unbounded reals (forces and speeds have no bound a hand guarantees)."""
        return spaces.Box(-np.inf, np.inf, shape=(self.size,), dtype=np.float32)

    def split(self, vector: np.ndarray) -> dict[str, np.ndarray]:
        """The vector's parts by name."""
        out, at = {}, 0
        for name, length in parts(self.motors, self.digits):
            out[name] = vector[at:at + length]
            at += length
        return out


class Watcher:
    """Reads a trial's observation each step; keeps the object's last pose relative to
    the palm for its velocity (by difference over the step: the frames carry poses)."""

    def __init__(self, layout: ObservationLayout, seconds_per_step: float) -> None:
        self.layout = layout
        self.dt = seconds_per_step
        self._last: tuple[Vec, Vec] | None = None

    def reset(self) -> None:
        self._last = None

    def observe(self, trial: Trial, t: float, goal: Vec,
                motion: tuple[list[float], list[float]] | None = None) -> np.ndarray:
        """The vector at ``t``, with ``goal`` the object's place it should be (scene units)
        and ``motion`` the motors' speeds and torques when read already (else asked)."""
        seen = Observation(trial, t, motion)
        position, quaternion = seen.object_position, seen.object_quaternion
        velocity, spin = self._motion(position, quaternion)
        palm = conjugate(trial.hand_quaternion())
        towards = [trial.scale.metres(g - h) for g, h in zip(goal, trial.hand_position())]
        values = [t, *seen.angles, *seen.speeds, *seen.torques, *seen.digit_forces, *position,
                  *quaternion, *velocity, *spin, *rotate(palm, towards),
                  *product(palm, trial.start_quaternion)]
        return np.asarray(values, dtype=np.float32)

    def _motion(self, position: Vec, quaternion: Vec) -> tuple[Vec, Vec]:
        last, self._last = self._last, (position, quaternion)
        if last is None:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        velocity = tuple((a - b) / self.dt for a, b in zip(position, last[0]))
        return velocity, tuple(v / self.dt for v in turn_vector(product(quaternion, conjugate(last[1]))))


def turn_vector(q: Vec) -> tuple[float, float, float]:
    """The unit quaternion ``q`` as axis × angle (rad), the short way round."""
    x, y, z, w = q if q[3] >= 0 else [-v for v in q]
    sine = math.sqrt(x * x + y * y + z * z)
    if sine < 1e-12:
        return (0.0, 0.0, 0.0)
    angle = 2 * math.atan2(sine, w)
    return (x / sine * angle, y / sine * angle, z / sine * angle)
