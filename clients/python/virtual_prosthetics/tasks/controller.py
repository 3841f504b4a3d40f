"""The baseline grasp controller: a scripted approach, closure, lift and hold, the same for
every trial of a grip and for every hand (it closes a hand by its grip map); no learning.
A user's controller is any function ``(trial, t)`` that moves ``trial.hand`` at ``t``
seconds into the trial (see :class:`Phases` for when the task observes)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from ..robots import Robot
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
    """How the baseline closes on one object, for any hand: how far its digits close
    (``close``: a share of each closing motor's way from open to closed; ``thumb``: the
    opposing digit's, None: the same), the least torque its motors drive with (a human
    hand's N·m; a stronger motor keeps its own), where the object lies under the hand
    (:class:`~.trial.Placement`: ``reach``, ``side``, ``gap``), how many seconds before
    the others the opposing digit starts closing (``lead``: it must be behind the object
    before they push it), and how many digits close (``digits``: the opposing one and
    those nearest it; None: all)."""

    close: float
    torque: float
    reach: float = 0.0
    side: float = 0.0
    gap: float = 0.0027
    thumb: float | None = None
    lead: float = 0.4
    digits: int | None = None


def smooth(t: float, start: float, span: float) -> float:
    """0 before ``start``, 1 after ``start + span``, easing in and out between (no jerk at
    either end: a hand that stops dead shakes what it holds)."""
    x = min(1.0, max(0.0, (t - start) / span))
    return x * x * (3 - 2 * x)


def baseline(grip: Grip, phases: Phases = PHASES) -> Control:
    """The scripted controller of ``grip``: down (the opposing digit preshaped from the
    start), the opposing digit then the others closed, up."""

    def control(trial: Trial, t: float) -> None:
        x, y, z = trial.home
        down = smooth(t, phases.hover, phases.descend)
        up = smooth(t, phases.lifting, phases.lift)
        trial.hand.set_position(x, y + trial.lift * (1 - down) + trial.lift * up, z)
        trial.hand.set_angles(*trial.grip.angles(shares(trial, grip, t, phases)))

    return control


def shares(trial: Trial, grip: Grip, t: float, phases: Phases = PHASES) -> dict[int, float]:
    """How far the baseline has closed each digit of ``grip`` at ``t``."""
    closing = trial.grip.nearest(grip.digits)
    out = {}
    for index in range(len(trial.grip.digits)):
        if index == trial.grip.opposing:
            share = grip.close if grip.thumb is None else grip.thumb
            out[index] = share * smooth(t, phases.closing - grip.lead, phases.close)
        else:
            out[index] = grip.close * smooth(t, phases.closing, phases.close) if index in closing else 0.0
    return out


def prepare(hand: Robot, grip: Grip) -> None:
    """The hand's motors at least as strong as the grip says."""
    for motor in hand.get_motors():
        if motor.get_max_torque() < grip.torque:
            motor.set_max_torque(grip.torque)
