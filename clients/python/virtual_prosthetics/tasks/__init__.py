"""Hand-function tests, run in a scene of a server that any viewer can watch:

- ``grasp``: SHAP's six grip patterns, a light and a heavy object each (:mod:`.grasp`);
- ``box-and-blocks``: blocks moved over the partition in 60 s (:mod:`.box_and_blocks`);
- ``hold``: a ball held while the hand moves along a path; drops (:mod:`.hold`);
- ``relocate``: the ball or cube brought to a target, MyoSuite's criteria (:mod:`.relocate`).

Any hand (:mod:`.hands`): a 1.0 hand, a robot file, a function that builds one, or a robot
in the scene, closed by its grip map (:mod:`.grip`). Objects are real sizes in the scene's
units (:mod:`.scale`). Each task has a scripted baseline controller; pass your own as
``controller=`` (or ``--controller module:function``).
"""

from __future__ import annotations

import argparse
from typing import Any, Callable

from ..session import Session
from . import box_and_blocks, grasp, hold, relocate
from .trial import TaskHand


def _controller(args: argparse.Namespace) -> dict[str, Any]:
    """The hand controller named with ``--controller``, as a task's keyword (none: its own)."""
    return {"controller": args.controller} if args.controller else {}


def _grasp(session: Session, hands: TaskHand, args: argparse.Namespace) -> dict[str, Any]:
    patterns = args.grips.split(",") if args.grips else grasp.PATTERN_NAMES
    unknown = sorted(set(patterns) - set(grasp.PATTERN_NAMES))
    if unknown:
        raise SystemExit(f"unknown grip {', '.join(unknown)}; the grips are {', '.join(grasp.PATTERN_NAMES)}")
    return grasp.grasp(session, hands, args.trials, args.seed, side_by_side=args.side_by_side,
                       patterns=patterns, **_controller(args))


def _box_and_blocks(session: Session, hands: TaskHand, args: argparse.Namespace) -> dict[str, Any]:
    return box_and_blocks.box_and_blocks(session, hands, args.seed, **_controller(args))


def _hold(session: Session, hands: TaskHand, args: argparse.Namespace) -> dict[str, Any]:
    return hold.hold(session, hands, args.trials, args.seed, side_by_side=args.side_by_side,
                     **_controller(args))


def _relocate(session: Session, hands: TaskHand, args: argparse.Namespace) -> dict[str, Any]:
    return relocate.relocate(session, hands, args.trials, args.seed, side_by_side=args.side_by_side,
                             **_controller(args))


TASKS: dict[str, Callable[[Session, TaskHand, argparse.Namespace], dict[str, Any]]] = {
    "grasp": _grasp, "box-and-blocks": _box_and_blocks, "hold": _hold, "relocate": _relocate}

__all__ = ["TASKS", "TaskHand"]
