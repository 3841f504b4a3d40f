"""The baseline grasp controller: a scripted approach, closure, lift and hold, the same for
every trial of a grip; no learning. A user's controller is any function ``(trial, t)`` that
moves ``trial.hand`` at ``t`` seconds into the trial (see :class:`Phases` for when the task
observes)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from .trial import Trial


# a controller: moves ``trial.hand`` at ``t`` seconds into the trial
Control = Callable[[Trial, float], None]


@dataclass(frozen=True)
class Phases:
    """A grasp's timeline in seconds: hover, descend, wait, close, squeeze, lift, hold."""

    hover: float = 0.3
    descend: float = 0.5
    wait: float = 0.3
    close: float = 0.67
    squeeze: float = 0.5
    lift: float = 1.0
    hold: float = 3.0

    @property
    def closing(self) -> float:
        return self.hover + self.descend + self.wait

    @property
    def lifting(self) -> float:
        return self.closing + self.close + self.squeeze

    @property
    def holding(self) -> float:
        """When the hold begins: the task observes from here to :attr:`end`."""
        return self.lifting + self.lift

    @property
    def end(self) -> float:
        return self.holding + self.hold


PHASES = Phases()


# The thumb's motors and angles that turn it to face the fingers, per hand (palm down, a
# thumb left as 1.0 builds it curls beside the palm, parallel to the fingers, and pushes
# what it should hold towards the wrist). Motor numbers are the hand's own (getMotors).
OPPOSED_THUMB: dict[str, dict[int, float]] = {
    "edged": {0: -1.0},   # the spread motor, turned back towards the wrist
    "round": {0: 0.4},    # the thumb's spread (MotorY)
    "anthro": {0: 0.5},   # the thumb's 'Palm' motor
}


@dataclass(frozen=True)
class Grip:
    """How the baseline closes on one object: finger angle when closed (radians), motor
    torque (a human hand's N·m), where the object lies under the hand (``reach`` hand
    lengths past the palm's end, ``side`` metres towards the thumb), and the gap
    between palm and object when the hand comes down (human metres). ``thumb``: the
    thumb's own flex when closed (None: as the fingers); ``lead``: how many seconds
    before the fingers the thumb starts closing (it must be behind the object before the
    fingers push it); ``fingers``: which fingers close (the others stay straight)."""

    flex: float
    torque: float
    reach: float
    side: float = 0.0
    gap: float = 0.0027
    thumb: float | None = None
    lead: float = 0.4
    fingers: tuple[int, ...] = (0, 1, 2, 3, 4)


def smooth(t: float, start: float, span: float) -> float:
    """0 before ``start``, 1 after ``start + span``, easing in and out between (no jerk at
    either end: a hand that stops dead shakes what it holds)."""
    x = min(1.0, max(0.0, (t - start) / span))
    return x * x * (3 - 2 * x)


def baseline(grip: Grip, phases: Phases = PHASES) -> Control:
    """The scripted controller of ``grip``: the thumb turned to face the fingers while the
    hand hovers, down, the thumb then the fingers closed, up."""
    opposed: set[str] = set()  # the hands whose thumbs were turned

    def control(trial: Trial, t: float) -> None:
        if trial.hand.id not in opposed:
            opposed.add(trial.hand.id)
            motors = trial.hand.get_motors()
            for index, angle in OPPOSED_THUMB[trial.kind].items():
                motors[index].set_angle(angle)
        x, y, z = trial.home
        down = smooth(t, phases.hover, phases.descend)
        up = smooth(t, phases.lifting, phases.lift)
        trial.hand.set_position(x, y + trial.lift * (1 - down) + trial.lift * up, z)
        for finger in grip.fingers:
            if finger == 0:
                angle = grip.flex if grip.thumb is None else grip.thumb
                closed = smooth(t, phases.closing - grip.lead, phases.close)
            else:
                angle, closed = grip.flex, smooth(t, phases.closing, phases.close)
            trial.hand.flex_finger(finger, angle * closed)  # type: ignore[attr-defined]

    return control


def prepare(trial: Trial, grip: Grip) -> None:
    """The hand's motors as strong as the grip says (scaled to the hand)."""
    torque = grip.torque
    for motor in trial.hand.get_motors():
        motor.set_max_torque(torque)
