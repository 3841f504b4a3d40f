"""``hold``: the spherical grasp's ball, lifted, then carried along a path (a circle in the
hand's plane and back, at a brisk human pace); a drop is a ball that left the hand."""

from __future__ import annotations

import math
import random
from typing import Any, Callable

from ..session import Session
from . import progress
from .controller import PHASES, Arm, Grip, approach, baseline
from .observation import HandController
from .grasp import LIFTED, PATTERNS, PHYSICS, Score, drawn, draws, rows, run_trials
from .scale import Scale
from .trial import TaskHand, Trial

RADIUS = 0.1   # metres (human): the circle the wrist goes round
PERIOD = 2.0   # seconds a round takes
ROUNDS = 2
DROPPED = 0.5  # × the ball's size: further than this from where it sat in the hand
SETTLE = 0.5   # seconds still after the path before the ball's place in the hand is read


def carry(scale: Scale, arm: Arm) -> Arm:
    """The wrist by ``arm`` until the hold begins, then round a circle in the x-y plane."""
    radius = scale.length(RADIUS)

    def step(trial: Trial, t: float) -> None:
        if t < PHASES.holding:
            arm(trial, t)
            return
        angle = 2 * math.pi * min(ROUNDS, (t - PHASES.holding) / PERIOD)
        x, y, z = trial.home
        trial.set_wrist(x + radius * math.sin(angle),
                        y + trial.lift + radius * (1 - math.cos(angle)), z)

    return step


def dropped(trial: Trial) -> bool:
    """Whether the ball left the hand during the path (or was never lifted): low at any
    time, or moved in the hand, judged where it sits in the still hand after the path
    against before it. (Not during the path: the hand's place a client knows is the one
    it sent, the ball's is a frame old, and at the path's speed that alone looked like a
    drop: every ball "dropped" while the pictures showed them held.)"""
    if len(trial.offsets) < 2 or min(trial.heights) < LIFTED * trial.layout.length:
        return True  # never lifted, or down at the table at some time
    moved = trial.scale.metres(math.dist(trial.offsets[0], trial.offsets[-1]))
    return moved > DROPPED * trial.item.extent


def hold(session: Session, hands: TaskHand, trials: int, seed: int, *, side_by_side: int = 10,
         controller: Callable[[Grip], HandController] = baseline) -> dict[str, Any]:
    """``trials`` balls (masses and frictions drawn from ``seed``), each carried round the
    path; the drops."""
    # paused first: a scene another run steps is refused before anything of it changes
    with session.paused():  # stepped tick by tick (drive): the same run on any load
        session.set_physics("dynamic", **PHYSICS)
        session.sync()
        scale = Scale.of(session)
        pattern = PATTERNS[0]
        grip = pattern.grip
        seconds = PHASES.holding + ROUNDS * PERIOD + SETTLE
        with progress.shown(rows(trials, side_by_side, hands) * seconds, f"hold {hands.source.name}"):
            done = run_trials(session, hands, pattern.item, draws(random.Random(seed), trials),
                              pattern.item.light, grip, carry(scale, approach()), controller,
                              side_by_side, seconds,
                              Score(f"carrying the {pattern.item.name}", "kept",
                                    lambda trial: not dropped(trial)))
        return {"task": "hold", "hand": hands.source.name, "seed": seed, "trials": trials,
                "object": pattern.item.name, "path": {"radiusM": RADIUS, "periodS": PERIOD,
                                                      "rounds": ROUNDS},
                "drops": sum(dropped(trial) for trial in done),
                "each": [{**drawn(trial), "dropped": dropped(trial)} for trial in done]}
