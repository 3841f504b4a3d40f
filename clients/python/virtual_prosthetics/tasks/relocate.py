"""``relocate``: pick the object up and bring it to a target, MyoSuite's relocate task at
the hand's size: a trial succeeds when the object is within 25 mm and 0.262 rad (15°) of
the target for more than 5 steps in a row; one that drops it (300 mm, or back down at the
table, which is nearer: within 20 % of the hand's length of it) fails. The target is the
object's start pose, raised and moved aside (:data:`TARGET`); the baseline grasps as
``grasp`` does, then steers and turns the wrist by where and how the object sits in the
hand, not where it was laid."""

from __future__ import annotations

import math
import random
from typing import Any, Callable

from ..session import Session
from . import progress
from .controller import PHASES, Arm, Grip, approach, baseline, smooth
from .grasp import LIFTED, PATTERNS, PHYSICS, Score, drawn, draws, rows, run_trials
from .observation import HandController, conjugate, product, rotate
from .scale import Scale
from .trial import TaskHand, Trial

TARGET = (0.10, 0.05, 0.0)  # metres (human): from the lifted object, aside and up
POSITION = 0.025    # metres: how near the target
ANGLE = 0.262       # radians: how little turned from it
STEPS = 5           # more steps in a row than this, both within
DROP = 0.3          # metres: a fall this far fails
MOVE = 1.0          # seconds the baseline's wrist takes to the target
SETTLE = 1.0        # seconds at the target


def target_of(trial: Trial) -> tuple[float, ...]:
    """Where the object should end (scene units): where it lay, lifted, moved by TARGET."""
    return tuple(a + trial.scale.length(b) + (trial.lift if i == 1 else 0.0)
                 for i, (a, b) in enumerate(zip(trial.start, TARGET)))


def steer(arm: Arm) -> Arm:
    """``arm`` until the hold begins; then the wrist glides and turns so that the object,
    where and as it is in the hand at that moment, comes to the target's place and turn
    (closing rolls a ball and tilts a cube by half a radian or more)."""
    aims: dict[int, tuple[Pose, Pose]] = {}

    def step(trial: Trial, t: float) -> None:
        if t < PHASES.holding:
            arm(trial, t)
            return
        if id(trial) not in aims:
            aims[id(trial)] = _aim(trial)
        (p0, q0), (p1, q1) = aims[id(trial)]
        share = smooth(t, PHASES.holding, MOVE)
        trial.hand.set_position(*(a + (b - a) * share for a, b in zip(p0, p1)))
        trial.hand.set_quaternion(list(_nlerp(q0, q1, share)))

    return step


Pose = tuple[tuple[float, ...], tuple[float, ...]]


def _aim(trial: Trial) -> tuple[Pose, Pose]:
    """The hand's pose now, and where it must be for the object it holds to be at the
    target: the turn from the object's to the target's, about the object."""
    hand, hand_q = tuple(trial.hand_position()), tuple(trial.hand_quaternion())
    obj, obj_q = trial.object_position(), trial.object_quaternion()
    turn = product(trial.start_quaternion, conjugate(obj_q))
    arm = rotate(turn, [h - o for h, o in zip(hand, obj)])
    return (hand, hand_q), (tuple(g + a for g, a in zip(target_of(trial), arm)), product(turn, hand_q))


def _nlerp(q: tuple[float, ...], r: tuple[float, ...], share: float) -> tuple[float, ...]:
    """From ``q`` to ``r`` the short way, normalised (near enough a slerp for a wrist)."""
    sign = 1.0 if sum(a * b for a, b in zip(q, r)) >= 0 else -1.0
    mixed = [a + (sign * b - a) * share for a, b in zip(q, r)]
    norm = math.sqrt(sum(v * v for v in mixed))
    return tuple(v / norm for v in mixed)


def turn_between(q: list[float] | tuple[float, ...], r: list[float] | tuple[float, ...]) -> float:
    """The angle of the turn between two unit quaternions."""
    dot = min(1.0, abs(sum(a * b for a, b in zip(q, r))))
    return 2 * math.acos(dot)


def judge(trial: Trial) -> dict[str, Any]:
    """Whether the trial succeeded by MyoSuite's rule, with its closest approach."""
    target = target_of(trial)
    run = best = 0
    nearest = math.inf
    for position, quaternion in trial.poses:
        distance = trial.scale.metres(math.dist(position, target))
        nearest = min(nearest, distance)
        run = run + 1 if distance < POSITION and turn_between(quaternion, trial.start_quaternion) < ANGLE else 0
        best = max(best, run)
    lowest = min((p[1] for p, _ in trial.poses), default=trial.start[1])
    fell = trial.scale.metres(max((p[1] for p, _ in trial.poses), default=lowest) - lowest)
    down = min(trial.heights, default=0.0) < LIFTED * trial.layout.length  # back at the table
    dropped = fell >= DROP or down
    turned = min((turn_between(q, trial.start_quaternion) for _, q in trial.poses), default=math.inf)
    return {"success": best > STEPS and not dropped, "dropped": dropped,
            "nearestM": round(nearest, 4), "leastTurnRad": round(turned, 3), "stepsWithin": best}


def relocate(session: Session, hands: TaskHand, trials: int, seed: int, *, side_by_side: int = 10,
             patterns: tuple[str, ...] = ("spherical", "tripod"),
             controller: Callable[[Grip], HandController] = baseline) -> dict[str, Any]:
    """``trials`` of each pattern's light object (masses and frictions drawn from
    ``seed``), each taken to its target; the successes."""
    with session.paused():  # stepped tick by tick (drive): the same run on any load
        session.set_physics("dynamic", **PHYSICS)
        session.sync()
        scale = Scale.of(session)
        rng = random.Random(seed)
        seconds = PHASES.holding + MOVE + SETTLE
        chosen = [p for p in PATTERNS if p.name in patterns]
        results = []
        planned = len(chosen) * rows(trials, side_by_side, hands) * seconds
        with progress.shown(planned, f"relocate {hands.source.name}"):
            for pattern in chosen:
                done = run_trials(session, hands, pattern.item, draws(rng, trials), pattern.item.light,
                                  pattern.grip, steer(approach()), controller, side_by_side,
                                  seconds,
                                  Score(f"{pattern.item.name} to its target", "placed",
                                        lambda trial: judge(trial)["success"]))
                judged = [{**drawn(trial), **judge(trial)} for trial in done]
                results.append({"grip": pattern.name, "object": pattern.item.name, "trials": len(done),
                                "successes": sum(j["success"] for j in judged),
                                "drops": sum(j["dropped"] for j in judged), "each": judged})
        return {"task": "relocate", "hand": hands.source.name, "seed": seed, "scale": scale.factor,
                "unit": scale.unit, "targetM": list(TARGET),
                "criteria": {"positionM": POSITION, "angleRad": ANGLE, "steps": STEPS, "dropM": DROP},
                "results": results}
