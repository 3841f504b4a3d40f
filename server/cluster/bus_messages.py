"""What the cluster's processes say to each other over the bus (:mod:`.bus`), one
dataclass per message; a scene's own commands and events travel inside them
(:mod:`server.web.process.messages`).

==================================  ============================  =========================
subject                             message                       answer
==================================  ============================  =========================
``vp.place``                        (none)                        :class:`Load`
``vp.loads``                        :class:`Load` (told)
``vp.worker.<w>.attach``            :class:`Attach`               :class:`Attached`,
                                                                  :class:`Full` or
                                                                  :class:`Elsewhere`
``vp.worker.<w>.alive``             attachment and scene pairs    the attachments it runs
``vp.worker.<w>.scene.<s>``         :class:`SceneCommands`
``vp.gateway.<g>.alive``            attachments                   those the gateway holds
``vp.scene.<s>.events``             :class:`SceneEvents`
==================================  ============================  =========================
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Union

from ..web.process.messages import Command, Event, ProcessMessage, message


@dataclass(frozen=True)
class NoRoom:
    """Why a worker takes no more scenes: the limit (a wire name of ``limit_exceeded``),
    its value, the flag of ``vp-server --role worker`` that changes it, and in words."""

    limit: str
    value: float
    flag: str
    text: str


@dataclass(frozen=True)
class Load:
    """How busy a worker is: its attended scenes and why it has no room (None: it has),
    as it was at ``stamp``, the worker's own monotonic clock (of two loads of one worker,
    the one stamped later is the newer, whichever way each came: a survey, a placement's
    answer or a change told)."""

    worker: str
    scenes: int
    room: NoRoom | None
    stamp: float


@message
class Attach(ProcessMessage):
    """A gateway asks a worker to run a scene for one of its attachments."""

    attachment: str
    scene: str
    expecting: bool  # a client waits for it: it counts as attended at once


@message
class Attached(ProcessMessage):
    """The worker runs the scene for the attachment now: what the attachment has missed."""

    pid: int | None
    incarnation: str  # the scene's process on the worker: its events carry it
    ready: list[str] | None  # the owners of its objects, once it is made
    saving: dict[str, Any]  # what it last said of its files
    asleep: bool  # it ticks no more until sent something: silent, not stuck
    load: Load  # the worker's, this scene included


@message
class Full(ProcessMessage):
    """The worker has no room (any more) for a new scene."""

    load: Load


@message
class Elsewhere(ProcessMessage):
    """Another worker holds the scene's lease."""

    holder: str


AttachAnswer = Union[Attached, Full, Elsewhere]


@message
class SceneCommands(ProcessMessage):
    """An attachment's commands for its scene, in the order posted."""

    attachment: str
    commands: list[Command]


@message
class Addressed(ProcessMessage):
    """A scene's event for one attachment (a connection's) or, ``attachment`` None, all."""

    attachment: str | None
    event: Event


@message
class SceneEvents(ProcessMessage):
    """What a scene said, published once for every gateway attached to it."""

    incarnation: str
    events: list[Addressed]
