"""What a hand's controller sees each step and what it answers, as a real controller
would: time, each motor's angle, speed and effort, each digit's force on the object (not
on the table beside it), and the object's pose relative to the palm; it answers motor
targets, angles or torques (:data:`HandController`).

Angles and the object's pose come with the frames the client already has; speeds and
torques are asked of the server the first time a controller reads them in a step (a
round trip each: a controller that never reads them costs nothing)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Callable, Sequence, Union

from .grip import HandGrip

if TYPE_CHECKING:
    from .trial import Trial


@dataclass(frozen=True)
class Angles:
    """Targets: each motor's angle (radians; a slider's length), in motor order; None
    leaves a motor as it is."""

    values: Sequence[float | None]


@dataclass(frozen=True)
class Torques:
    """Targets: the torque each motor drives with (N·m; a slider's force, N; dynamic mode),
    positive turning its angle up; None leaves a motor as it is. A motor so driven turns
    until its limit or what it presses stops it (Bullet's motor at its bound, aimed at
    the limit the torque points to)."""

    values: Sequence[float | None]


Targets = Union[Angles, Torques]


class Observation:
    """One step of one trial as its hand's controller sees it."""

    def __init__(self, trial: Trial, t: float,
                 motion: tuple[list[float], list[float]] | None = None) -> None:
        self.t = t
        """Seconds since the trial began."""
        self.grip: HandGrip = trial.grip
        """The hand's digits (which motors close which) and layout."""
        self._trial = trial
        if motion is not None:  # speeds and torques read with the step (Session.step_reading)
            self.__dict__["speeds"], self.__dict__["torques"] = motion

    @cached_property
    def angles(self) -> list[float]:
        """Each motor's angle now (radians; a slider's length), in motor order."""
        return self._trial.hand.get_angles()

    @cached_property
    def speeds(self) -> list[float]:
        """Each motor's speed at the last step (rad/s), in motor order (asks the server)."""
        return self._trial.hand.get_speeds()

    @cached_property
    def torques(self) -> list[float]:
        """The torque each motor drove with in the last step (N·m), in motor order (asks
        the server): a servo's current."""
        return self._trial.hand.get_torques()

    @cached_property
    def digit_forces(self) -> list[float]:
        """Each digit's normal force on the object (N), by the grip map's digits: what
        its parts press on the object with, whatever they press elsewhere."""
        pressing = {c["other"]: c["normal"] for c in self._trial.object_contacts()}
        return [sum(pressing.get(part, 0.0) for part in digit.parts) for digit in self.grip.digits]

    @cached_property
    def object_position(self) -> tuple[float, float, float]:
        """Where the object's centre is from the hand's, in the hand's own frame (metres)."""
        offset = [self._trial.scale.metres(v) for v in self._trial.object_offset()]
        return rotate(conjugate(self._trial.hand_quaternion()), offset)

    @cached_property
    def object_quaternion(self) -> tuple[float, float, float, float]:
        """The object's turn relative to the hand's, as a quaternion (x, y, z, w)."""
        hand, obj = self._trial.hand_quaternion(), self._trial.object_quaternion()
        return product(conjugate(hand), obj)


FAR = 1e3  # radians (a slider's length): where a torque target aims a motor

# a controller: an observation in, targets out (None: leave every motor as it is)
HandController = Callable[[Observation], Union[Targets, None]]


def apply(trial: Trial, targets: Targets | None, previous: dict[int, float]) -> None:
    """Send ``targets`` to the trial's hand. Torques drive each motor at its bound towards
    the limit they point to; ``previous`` (the torques last sent, by motor index) keeps
    unchanged ones from being sent again."""
    if targets is None:
        return
    if isinstance(targets, Angles):
        previous.clear()
        trial.set_motors(*targets.values)
        return
    motors = trial.hand.get_motors()
    angles: list[float | None] = [None] * len(motors)
    for index, (motor, torque) in enumerate(zip(motors, targets.values)):
        if torque is None or previous.get(index) == torque:
            continue
        previous[index] = torque
        motor.set_max_torque(max(abs(torque), 1e-9))
        # far beyond any limit: the server clamps it to the limit, and the motor strains
        # at its bound all the way there
        angles[index] = math.copysign(FAR, torque)
    trial.set_motors(*angles)


# Written here, not imported: the client depends on websockets alone
def conjugate(q: Sequence[float]) -> tuple[float, float, float, float]:
    """The inverse turn of the unit quaternion ``q`` (x, y, z, w)."""
    return (-q[0], -q[1], -q[2], q[3])


def product(a: Sequence[float], b: Sequence[float]) -> tuple[float, float, float, float]:
    """The turn ``b`` then ``a``, as quaternions (x, y, z, w)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def rotate(q: Sequence[float], v: Sequence[float]) -> tuple[float, float, float]:
    """``v`` turned by the quaternion ``q`` (x, y, z, w)."""
    x, y, z, _ = product(product(q, (*v, 0.0)), conjugate(q))
    return (x, y, z)
