"""What each environment's episode is: the hand-function task it is built on, where the
object should be at each moment, when it is solved, when it is lost, and the reward.

Rewards are MyoSuite's for the same tasks, at the hand's size in metres (a robot's at its
own size; a 1.0 hand's at a human hand's):

- Grasp and Hold, as ``myoHandObjHoldFixed``: ``-100·d + 4·((d < 2·10 mm) + (d < 10 mm))
  - 10·dropped``, ``d`` the object's distance from where it should be: where it lay
  until the lift begins, then moved as the wrist has moved since it held it (a held object
  goes where the wrist goes; one left behind is as far as the wrist went without it).
- Relocate, as ``myoChallengeRelocate``: ``-100·d - θ``, ``d`` from the task's target and
  ``θ`` the object's turn from its start (radians).

Steps are scored from the lift on; before it a step's reward is 0. MyoSuite's ObjHold
starts with the object in the hand; these episodes begin with the approach, when there is
nothing to hold yet, and scoring it gave every hand that leaves the object alone a bonus a
step (8 while the object lay still): learners learnt not to touch it.

An episode ends (``terminated``) when the object is dropped as its task judges a drop (back
down at the table after the lift, or fallen 300 mm; Hold: out of the hand by half its
size), and is cut off (``truncated``) when the task's time is up. ``info["success"]`` is
the task's own verdict (:func:`~..tasks.grasp.succeeded`, :func:`~..tasks.hold.dropped`,
:func:`~..tasks.relocate.judge`) on the episode so far: on the last step, the trial's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

from ..tasks import grasp, hold, relocate
from ..tasks.controller import PHASES, Arm, approach
from ..tasks.grasp import LIFTED, PATTERNS
from ..tasks.scale import Scale
from ..tasks.trial import Trial

GOAL = 0.010      # metres: MyoSuite's ObjHold threshold (its bonus at twice and once it)
DROP_FALL = 0.3   # metres fallen: a drop (MyoSuite's ObjHold and the relocate task's)

Vec = tuple[float, ...]
Grasped = tuple[Vec, Vec]  # the object's and the wrist's positions when the hold began


@dataclass(frozen=True)
class Episode:
    """One environment's task: its wrist path, length, goal, verdicts and reward."""

    name: str
    patterns: tuple[str, ...]  # the grips (by object) it offers
    seconds: float
    arm: Callable[[Scale], Arm]
    goal: Callable[[Trial, float, Grasped | None], Vec]  # where the object should be at t
    success: Callable[[Trial], bool]
    dropped: Callable[[Trial], bool]
    reward: Callable[[float, float, bool], float]  # (distance m, turn rad, dropped)


def follows_wrist(trial: Trial, t: float, held: Grasped | None) -> Vec:
    """Where the object lay until the lift begins; during it, raised as far as the wrist
    has risen; from the hold on, where it was in the hand when the hold began, moved as the
    wrist has moved since (the task's slip is measured from there)."""
    if held is not None:
        held_at, wrist_at = held
        return tuple(o + now - w for o, now, w in zip(held_at, trial.hand_position(), wrist_at))
    risen = trial.hand_position()[1] - trial.home[1] if t >= PHASES.lifting else 0.0
    return (trial.start[0], trial.start[1] + max(0.0, risen), trial.start[2])


def fell(trial: Trial) -> bool:
    """Down at the table after the lift, or fallen :data:`DROP_FALL` from its highest."""
    if not trial.heights:
        return False
    if trial.heights[-1] < LIFTED * trial.layout.length:
        return True
    highest = max(p[1] for p, _ in trial.poses)
    return trial.scale.metres(highest - trial.poses[-1][0][1]) >= DROP_FALL


def held(trial: Trial) -> bool:
    """Hold's verdict so far: lifted, and (after the path) still where it sat in the hand."""
    return bool(trial.heights) and not hold.dropped(trial)


def out_of_hand(trial: Trial) -> bool:
    """Hold's drop as it happens: down at the table, or half its size from where it sat
    in the hand when the hold began."""
    if fell(trial):
        return True
    return len(trial.offsets) > 1 and trial.scale.metres(
        math.dist(trial.offsets[0], trial.offsets[-1])) > hold.DROPPED * trial.item.extent


def hold_reward(distance: float, _turn: float, dropped: bool) -> float:
    """MyoSuite's ObjHold reward."""
    bonus = (distance < 2 * GOAL) + (distance < GOAL)
    return -100.0 * distance + 4.0 * bonus - 10.0 * dropped


def relocate_reward(distance: float, turn: float, _dropped: bool) -> float:
    """MyoSuite's Relocate reward."""
    return -100.0 * distance - turn


def _grasp_success(trial: Trial) -> bool:
    return bool(trial.heights) and grasp.succeeded(trial)


def _relocate_success(trial: Trial) -> bool:
    return bool(relocate.judge(trial)["success"])


EPISODES: dict[str, Episode] = {
    "Grasp": Episode("Grasp", tuple(p.name for p in PATTERNS), PHASES.end, lambda scale: approach(),
                     follows_wrist, _grasp_success, fell, hold_reward),
    "Hold": Episode("Hold", ("spherical",), PHASES.holding + hold.ROUNDS * hold.PERIOD + hold.SETTLE,
                    lambda scale: hold.carry(scale, approach()), follows_wrist, held, out_of_hand,
                    hold_reward),
    "Relocate": Episode("Relocate", ("spherical", "tripod"),
                        PHASES.holding + relocate.MOVE + relocate.SETTLE,
                        lambda scale: relocate.steer(approach()), lambda trial, t, held: relocate.target_of(trial),
                        _relocate_success, fell, relocate_reward),
}

OBJECTS: dict[str, str] = {"sphere": "spherical", "cube": "tripod", "cylinder": "power",
                           "plate": "lateral", "tip": "tip", "card": "extension"}
"""Each grip pattern by its object's short name (``object=`` of the environments)."""
