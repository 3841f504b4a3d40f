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


@dataclass(frozen=True)
class Grip:
    """How the baseline closes on one object: finger angle when closed (radians), motor
    torque (a human hand's N·m), where the object lies under the hand (``reach`` hand
    lengths past the palm's end, ``side`` metres towards the thumb), and the gap
    between palm and object when the hand comes down (human metres). ``thumb``: the
    thumb's own flex when closed (None: as the fingers); ``fingers``: which fingers close
    (the others stay straight)."""

    flex: float
    torque: float
    reach: float
    side: float = 0.0
    gap: float = 0.0027
    thumb: float | None = None
    fingers: tuple[int, ...] = (0, 1, 2, 3, 4)


def _ramp(t: float, start: float, span: float) -> float:
    return min(1.0, max(0.0, (t - start) / span))


def baseline(grip: Grip, phases: Phases = PHASES) -> Control:
    """The scripted controller of ``grip``."""

    def control(trial: Trial, t: float) -> None:
        x, y, z = trial.home
        hover = trial.lift
        down = _ramp(t, phases.hover, phases.descend)
        up = _ramp(t, phases.lifting, phases.lift)
        trial.hand.set_position(x, y + hover * (1 - down) + trial.lift * up, z)
        closed = _ramp(t, phases.closing, phases.close)
        for finger in grip.fingers:
            angle = grip.thumb if finger == 0 and grip.thumb is not None else grip.flex
            trial.hand.flex_finger(finger, angle * closed)  # type: ignore[attr-defined]

    return control


def prepare(trial: Trial, grip: Grip) -> None:
    """The hand's motors as strong as the grip says (scaled to the hand)."""
    torque = trial.scale.torque(grip.torque)
    for motor in trial.hand.get_motors():
        motor.set_max_torque(torque)
