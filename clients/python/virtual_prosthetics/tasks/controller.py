"""The grasp tasks' controllers. The task moves the wrist (:func:`approach`: down, and up
once the hand has closed; see :class:`Phases` for when it observes); a hand controller
(:data:`~.observation.HandController`) is given an :class:`~.observation.Observation`
each step and answers the hand's motor targets. Two come with the tasks, for any hand
(both close it by its grip map): :func:`baseline`, scripted, and :func:`force_stop`, closed
loop: each digit closes until it presses the object with a force."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from ..robots import Robot
from .grip import HandGrip
from .observation import Angles, HandController, Observation
from .trial import Trial

# the wrist's path: moves ``trial.hand`` to where it is ``t`` seconds into the trial
Arm = Callable[[Trial, float], None]


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


def approach(phases: Phases = PHASES) -> Arm:
    """The wrist's path: over the object, down to it, and up once the hand has closed."""

    def arm(trial: Trial, t: float) -> None:
        x, y, z = trial.home
        down = smooth(t, phases.hover, phases.descend)
        up = smooth(t, phases.lifting, phases.lift)
        trial.set_wrist(x, y + trial.lift * (1 - down) + trial.lift * up, z)

    return arm


def baseline(grip: Grip, phases: Phases = PHASES) -> HandController:
    """The scripted hand of ``grip``: the opposing digit preshaped from the start, then
    it and the others closed, each to the grip's share, on a fixed timeline."""

    def control(seen: Observation) -> Angles:
        return Angles(seen.grip.angles(shares(seen.grip, grip, seen.t, phases)))

    return control


def shares(hand: HandGrip, grip: Grip, t: float, phases: Phases = PHASES) -> dict[int, float]:
    """How far the baseline has closed each digit of ``grip`` at ``t``."""
    closing = hand.nearest(grip.digits)
    out = {}
    for index in range(len(hand.digits)):
        if index == hand.opposing:
            share = grip.close if grip.thumb is None else grip.thumb
            out[index] = share * smooth(t, phases.closing - grip.lead, phases.close)
        else:
            out[index] = grip.close * smooth(t, phases.closing, phases.close) if index in closing else 0.0
    return out


STOP_FORCE = 1.0  # newtons: a light pinch (a human hand holds a 50 g object with ~1-2 N)


def force_stop(grip: Grip, force: float = STOP_FORCE, phases: Phases = PHASES) -> HandController:
    """A closed-loop hand: each digit of ``grip`` closes at the baseline's pace until it
    presses the object with ``force`` newtons while a digit across from it does too (the
    object squeezed between them: one digit alone only pushes it; the table does not
    count), then goes :data:`SQUEEZE` further and stays; one that never does closes as far
    as the baseline's."""
    stopped: dict[int, float] = {}

    def control(seen: Observation) -> Angles:
        planned = shares(seen.grip, grip, seen.t, phases)
        pressing = [f >= force for f in seen.digit_forces]
        for index, presses in enumerate(pressing):
            if index in stopped or not presses or planned.get(index, 0.0) <= 0:
                continue
            if any(p for j, p in enumerate(pressing) if _across(seen.grip, index, j)):
                stopped[index] = min(1.0, planned[index] + SQUEEZE)
        return Angles(seen.grip.angles({i: stopped.get(i, share) for i, share in planned.items()}))

    return control


def _across(hand: HandGrip, a: int, b: int) -> bool:
    """Whether digits ``a`` and ``b`` close against each other: one opposes and the other
    does not (without an opposing digit, any two do)."""
    if a == b:
        return False
    return hand.opposing < 0 or (a == hand.opposing) != (b == hand.opposing)


SQUEEZE = 0.1  # of a digit's way closed, past where it first pressed with the force


def prepare(hand: Robot, grip: Grip) -> None:
    """The hand's motors at least as strong as the grip says."""
    for motor in hand.get_motors():
        if motor.get_max_torque() < grip.torque:
            motor.set_max_torque(grip.torque)
