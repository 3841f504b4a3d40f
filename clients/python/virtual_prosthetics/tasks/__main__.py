"""``python -m virtual_prosthetics.tasks NAME --url ws://… --hand edged|round|anthro|FILE|
module:function [--robot ID] [--grip-map FILE] [--trials N] [--seed S]``: run a
hand-function task in a scene of a server (any viewer of that scene watches it) and print
its results as JSON."""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any, Callable, Sequence

from ..errors import ConnectionLost, ServerError, Timeout, VPError
from ..runtime import connect
from ..waiting import DEFAULT_SECONDS, ENVIRONMENT, wait_seconds
from . import TASKS, report
from .grip import read_grip_map
from .hands import BUILT_IN, hand_source, imported, robot_source
from .trial import TaskHand


def _function(spec: str) -> Callable[..., Any]:
    """``module:function`` (a user's controller)."""
    try:
        return imported(spec)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def parser() -> argparse.ArgumentParser:
    parse = argparse.ArgumentParser(prog="python -m virtual_prosthetics.tasks",
                                    description=__doc__.split("\n\n")[0])
    parse.add_argument("task", choices=sorted(TASKS),
                       help="or 'report' (its own options: report --help)")
    parse.add_argument("--url", default="ws://127.0.0.1:8000")
    parse.add_argument("--scene", default="tasks", help="the scene to run in (default: tasks)")
    parse.add_argument("--hand", default="edged",
                       help=f"{'|'.join(sorted(BUILT_IN))}, a robot file (URDF, MJCF, a zip or folder "
                            f"of one with its meshes), or module:function building one in the "
                            f"session it is given (default: edged)")
    parse.add_argument("--robot", metavar="ID", help="evaluate this robot of the scene instead")
    parse.add_argument("--grip-map", type=_grip_map, metavar="FILE",
                       help="the hand's digits and motors, instead of those derived from its "
                            "kinematics (JSON; see virtual_prosthetics.tasks.grip)")
    parse.add_argument("--trials", type=int, default=20, help="trials of each object (grasp, hold)")
    parse.add_argument("--seed", type=int, default=0)
    parse.add_argument("--side-by-side", type=int, default=10,
                       help="trials run at once, in a row (grasp, hold)")
    parse.add_argument("--grips", help="grasp: comma-separated patterns (default: all)")
    parse.add_argument("--controller", type=_function,
                       help="module:function making your controller (see the task's docs)")
    parse.add_argument("--token", help="the server's token, when it asks for one")
    parse.add_argument("--timeout", type=_seconds, metavar="S",
                       help="seconds to wait for the scene and for each answer (default: "
                            f"${ENVIRONMENT}, else {DEFAULT_SECONDS:g})")
    return parse


def _grip_map(path: str) -> dict[str, Any]:
    try:
        return read_grip_map(path)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def _seconds(text: str) -> float:
    try:
        return wait_seconds(float(text))
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def main(argv: Sequence[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["report"]:  # many runs at once, with files and a page (tasks/report.py)
        return report.main(argv[1:])
    args = parser().parse_args(argv)
    if args.trials < 1 or args.side_by_side < 1:
        parser().error("--trials and --side-by-side must be at least 1")
    try:
        session = connect(args.url, scene=args.scene, token=args.token, timeout=args.timeout)
        try:
            source = robot_source(args.robot, session) if args.robot else hand_source(args.hand, session)
            result = TASKS[args.task](session, TaskHand(source, args.grip_map), args)
        finally:
            session.close()
    except (VPError, ValueError) as error:
        print(f"error: {_fix(error, args.url)}", file=sys.stderr)
        return 1
    json.dump(result, sys.stdout, indent=2)
    print()
    return 0


def _fix(error: Exception, url: str) -> str:
    """What went wrong, in one line, and what to do about it."""
    if isinstance(error, Timeout):
        return (f"{error.what} within {error.seconds:g} s (--timeout S or {ENVIRONMENT}=S "
                f"waits longer)")
    if isinstance(error, ServerError) and error.code == "forbidden" and error.details.get("owner"):
        return f"{error.message} (another run in this scene? give each its own: --scene NAME)"
    if isinstance(error, ServerError) and error.code == "forbidden":
        return f"{error.message}: give the server's token with --token T (or VP_TOKEN=T)"
    if isinstance(error, ServerError) and error.code == "not_paused":
        return (f"{error.message}: another client resumed the scene while this run stepped "
                f"it (another run in this scene? give each its own: --scene NAME)")
    if isinstance(error, ServerError):
        return f"the server refused: {error}"
    if isinstance(error, ConnectionLost) and error.args[0].startswith("could not reach"):
        return f"{error}; start a server (make run) or give its address with --url"
    if isinstance(error, ConnectionLost):
        return f"{error}; the run did not finish"
    return f"{error} (--url {url!r})" if "WebSocket address" in str(error) else str(error)


if __name__ == "__main__":
    sys.exit(main())
