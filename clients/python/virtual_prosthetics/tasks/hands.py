"""Which hand a task evaluates (``--hand``, ``--robot``): a 1.0 hand by name, a robot file
(URDF, MJCF, or a zip or folder of one with its meshes), a Python function that builds a
hand in the session it is given and returns it (``module:function``), or a robot already
in the scene. No task knows a hand by name beyond making it: each closes it by its grip
map (:mod:`.grip`)."""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from ..robots import AnthroHand, EdgedHand, ImportedRobot, RoundHand, Robot
from ..session import Session
from ..uploads import upload_robot

BUILT_IN: dict[str, Callable[..., Robot]] = {"edged": EdgedHand, "round": RoundHand,
                                              "anthro": AnthroHand}


@dataclass(frozen=True)
class HandSource:
    """How a task gets its hands: ``make(session)`` makes one (for a robot already in the
    scene: gives that robot, which the task then does not remove: ``owned`` is false)."""

    name: str
    make: Callable[[Session], Robot]
    owned: bool = True


def hand_source(spec: str, session: Session) -> HandSource:
    """The source ``--hand`` names (see the module's docstring); ValueError when it names
    none, saying what it may be."""
    if spec in BUILT_IN:
        return HandSource(spec, lambda s: BUILT_IN[spec](True, scene=s))
    path = Path(spec)
    if path.exists():
        file = upload_robot(path, scene=session)
        return HandSource(path.stem, lambda s: ImportedRobot(file, scene=s))
    if ":" in spec:
        return HandSource(spec, _built_by(spec))
    raise ValueError(f"--hand {spec!r}: not one of {', '.join(sorted(BUILT_IN))}, not a robot file "
                     f"or folder here, and not module:function")


def robot_source(robot_id: str, session: Session) -> HandSource:
    """A robot already in the scene (``--robot ID``), evaluated where it is."""
    robot = session.resolve(robot_id)
    if not isinstance(robot, Robot):
        raise ValueError(f"--robot {robot_id!r}: no robot of that id in scene {session.name!r} "
                         f"(GET /api/scenes/{session.name}/robots lists them)")
    return HandSource(robot_id, lambda s: robot, owned=False)


def imported(spec: str) -> Callable[..., Any]:
    """The function ``module:function`` names (a hand's builder, a controller); ValueError
    saying what to do when it cannot be had."""
    module, _, name = spec.partition(":")
    if not name:
        raise ValueError(f"expected module:function, got {spec!r}")
    try:
        return getattr(importlib.import_module(module), name)  # type: ignore[no-any-return]
    except ImportError as error:
        raise ValueError(f"cannot import {module!r} ({error}); run from the folder that holds "
                         f"it, or set PYTHONPATH") from None
    except AttributeError:
        raise ValueError(f"module {module!r} has no {name!r}") from None


def _built_by(spec: str) -> Callable[[Session], Robot]:
    """``module:function``: the function, checked to return the robot it built."""
    try:
        function = imported(spec)
    except ValueError as error:
        raise ValueError(f"--hand {spec!r}: {error}") from None

    def make(session: Session) -> Robot:
        robot = function(session)
        if not isinstance(robot, Robot):
            raise ValueError(f"--hand {spec!r}: the function returned {robot!r}, not the robot "
                             f"it built in the session it was given")
        return robot
    return make
