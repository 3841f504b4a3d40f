"""What the server and a scene's process say to each other: one dataclass per message.

The server sends a scene's process commands and gets events back, both in lists, through
the process's pipe (:mod:`server.web.scenes.runner`) or, in a cluster, over the bus to the
worker that runs the scene (:mod:`server.cluster.remote_runner`, which adds the gateway's
``Detach``). Every side takes a message apart with ``match``.

========================================  =============================================
command                                   events it causes
========================================  =============================================
``Join(cid, client_id, role, resume,      ``Admit(cid, [hello, snapshot])``
keep, trusted)``
``Text(cid, text)``                       ``Answers(cid, [answers], applied)``
``Leave(cid)``                            the client's objects deleted (seen in frames)
                                          after ``leaveGraceSeconds``, unless it comes
                                          back (joins as the same client) or keeps them
``Ask(n, question)``                      ``Reply(n, ok, body or VPError)``; questions:
``Read(function, args)``                  ``function(scene, *args)``, as JSON (its bytes
                                          as they are)
``Import(body, replace)``                 the scene replaced by a document's bytes (every
                                          client gets a warning and a new snapshot)
                                          unless it would take what clients here own;
                                          owners not connected get a grace period
``Place(file, position, quaternion)``     the robot of an uploaded robot file made, kept
                                          and shared, as the server's: its report
``Metrics()``                             recent figures (answered ahead of a backlog)
``Record(recording_id, path)``            a recording into ``path`` starts
``Unrecord(recording_id)``                it stops: what it holds
``Stop()``                                the process ends (its scene saved first; exit
                                          code SAVE_FAILED if its changes could not be)
``Detach()`` (a cluster's gateway)        ``Detached()``: its clients have left
a client's ``startRecording``             ``RecordingStarted(recording_id)``
any recording's end (asked, a limit,      ``Recorded(summary)``
the scene's end)
once made (or restored)                   ``Ready(owners)``: the owners of its objects
each tick                                 ``Frame([messages])`` for every client
nothing to do: it stops ticking           ``Idle()`` (silence is sleep, not a hang)
its files' state changed                  ``Saving(report)``
the process ended (or never started)      ``Ended(failed, refusal)``: made by its runner
========================================  =============================================

A connection's id (``cid``) is the server's number for it; a cluster's worker makes it
``(attachment, number)``, so connections of different gateways never collide.
"""

from __future__ import annotations

from dataclasses import dataclass
from operator import attrgetter
from typing import Any, Callable, TypeVar, Union

from ...core.kit.errors import VPError
from ..connections.outgoing import Outgoing

ConnectionId = Union[int, tuple[str, int]]
Message = TypeVar("Message", bound=type)


class ProcessMessage:
    """A message between processes. Pickled as its class and its fields' values, not
    their names: a flood sends thousands a second (a quarter of the bytes and time
    pickle's default takes for a slotted dataclass)."""

    __slots__ = ()
    _values: Callable[[Any], tuple[Any, ...]]

    def __reduce__(self) -> tuple[Any, ...]:
        return type(self), self._values(self)


def message(cls: Message) -> Message:
    """A dataclass with slots that pickles compactly (:class:`ProcessMessage`)."""
    made = dataclass(slots=True)(cls)
    names = made.__match_args__
    made._values = staticmethod(  # (attrgetter of one name gives no tuple)
        attrgetter(*names) if len(names) > 1 else lambda value: tuple(getattr(value, name) for name in names))
    return made


# Commands: to a scene's process

@message
class Join(ProcessMessage):
    cid: ConnectionId
    client_id: str
    role: str
    resume: str | None = None  # the resume key it was given in hello
    keep: bool = False  # what it makes stays when it leaves
    trusted: bool = False  # it presented the server's control token


@message
class Text(ProcessMessage):
    cid: ConnectionId
    text: str | bytes


@message
class Leave(ProcessMessage):
    cid: ConnectionId


@message
class Read(ProcessMessage):
    function: Callable[..., Any]  # a module's function (pickled by name): (scene, *args)
    args: tuple[Any, ...] = ()


@message
class Import(ProcessMessage):
    body: bytes
    replace: bool = False


@message
class Place(ProcessMessage):
    file: str
    position: tuple[float, float, float]
    quaternion: tuple[float, float, float, float]


@message
class Metrics(ProcessMessage):
    pass


@message
class Record(ProcessMessage):
    recording_id: str
    path: str


@message
class Unrecord(ProcessMessage):
    recording_id: str


Question = Union[Read, Import, Place, Metrics, Record, Unrecord]


@message
class Ask(ProcessMessage):
    number: int  # the Reply carries it back
    question: Question


@message
class Stop(ProcessMessage):
    pass


@message
class Detach(ProcessMessage):
    pass


Command = Union[Join, Text, Leave, Ask, Stop, Detach]


# Events: from a scene's process (Ended and Detached: from its runner)

@message
class Admit(ProcessMessage):
    cid: ConnectionId
    items: list[Outgoing]  # hello, snapshot


@message
class Answers(ProcessMessage):
    cid: ConnectionId
    items: list[Outgoing]
    applied: int  # bytes of the connection's text applied


@message
class Reply(ProcessMessage):
    number: int
    ok: bool
    value: Any  # JSON bytes (or a function's own bytes), figures, or the VPError


@message
class Ready(ProcessMessage):
    owners: list[str]


@message
class Frame(ProcessMessage):
    items: list[Outgoing]


@message
class Idle(ProcessMessage):
    pass


@message
class Saving(ProcessMessage):
    report: dict[str, Any]


@message
class RecordingStarted(ProcessMessage):
    recording_id: str


@message
class Recorded(ProcessMessage):
    summary: dict[str, Any]


@message
class Ended(ProcessMessage):
    failed: bool
    refusal: VPError | None = None  # why it never started (a cluster with no room)


@message
class Detached(ProcessMessage):
    pass


Event = Union[Admit, Answers, Reply, Ready, Frame, Idle, Saving, RecordingStarted,
              Recorded, Ended, Detached]
