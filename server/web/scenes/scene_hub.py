"""One scene as the event loop sees it: its process and the connections that receive its
messages (:class:`SceneHub`), each connection's outbox and text in flight (:class:`Connection`).

Every method here runs on the event loop; the scene itself lives in a process of its own
(:mod:`server.web.process.worker`), whose events arrive here in the order they were made
(:mod:`server.web.scenes.runner`).
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import logging
import time
from dataclasses import dataclass, field
from typing import Any, AsyncIterator, Callable

from ...core.kit.limits import Limits
from ...core.physics.assets import AssetLibrary
from ...core.kit.errors import UnknownScene, VPError
from ..connections.framed_socket import FramedSocket
from ..connections.outbox import Outbox, SlowConsumer
from ..connections.outgoing import Outgoing
from ..recording.recordings import Recordings
from .runner import RunnerFactory, SceneRunner
from ..storage.scene_store import SceneStore
from ..process.messages import (Admit, Answers, Ended, Event, Frame, Idle, Join, Leave, Ready,
                                Recorded, RecordingStarted, Saving, Text)
from ..process.scene_start import SceneSetup

log = logging.getLogger(__name__)
INFLIGHT_BYTES = 64 << 10  # text of a connection its scene has not applied yet, past which
# the server stops reading the connection (TCP slows the client): about 700 calls, 50 ms of
# the scene's work, so no other client waits longer than that behind a flooding one
REPLACED = 4001  # close code: the same client connected again; clients do not reconnect
SILENT_SECONDS = 3.0  # a scene that sent nothing this long (60 frames a second) is unresponsive
_numbers = itertools.count(1)


@dataclass(eq=False, slots=True)
class Connection:
    """A client as the loop sees it: its id and role, outbox, and text not yet applied."""

    client_id: str
    role: str
    outbox: Outbox
    resume: str | None = None  # sent in hello: how this client comes back as itself
    keep: bool = False  # what it made stays in the scene when it leaves
    trusted: bool = False  # it presented the server's control token
    number: int = field(default_factory=lambda: next(_numbers))
    closed: asyncio.Event = field(default_factory=asyncio.Event)
    admitted: asyncio.Event = field(default_factory=asyncio.Event)
    inflight: int = 0
    drained: asyncio.Event = field(default_factory=asyncio.Event)
    farewell: Outgoing | None = None  # the last message, sent as the connection closes
    close_code: int = 1000
    close_reason: str = ""
    socket: FramedSocket | None = None  # where frames made once are written, if offered
    # its socket while nothing of its own waits or is being written and it is open: where
    # a message goes straight (the same bytes for every viewer; messages never overtake)
    direct: FramedSocket | None = None

    def __post_init__(self) -> None:
        self.drained.set()
        self.direct = self.socket

    def send(self, items: list[Outgoing]) -> None:
        """Write messages, or queue them behind those waiting; a connection that stopped
        reading is marked closed."""
        try:
            for item in items:
                if self.direct is None or not self.direct.write_now(item.frame):
                    self.direct = None
                    self.outbox.put(item)
        except SlowConsumer as reason:
            if not self.closed.is_set():
                log.warning("closing %s: %s", self.client_id, reason)
            self.shut()

    async def take(self) -> Outgoing:
        """The next message waiting (its writer's): until :meth:`written`, nothing else
        goes straight to the socket."""
        item = await self.outbox.get()
        self.direct = None
        return item

    def written(self) -> None:
        """The message taken was written: messages go straight again once none waits."""
        if not self.outbox and not self.closed.is_set():
            self.direct = self.socket

    def shut(self) -> None:
        """Mark the connection closed: it takes no more messages."""
        self.direct = None
        self.closed.set()

    def applied(self, size: int) -> None:
        """``size`` bytes of this connection's text were applied by its scene."""
        self.inflight -= size
        if self.inflight <= INFLIGHT_BYTES:
            self.drained.set()


class SceneHub:
    """One scene: its process and the connections that receive its messages."""

    def __init__(self, name: str, limits: Limits, tick_rate: float, assets: AssetLibrary,
                 setup: SceneSetup | None = None, store: SceneStore | None = None,
                 owners: Callable[[list[str]], None] = lambda owners: None,
                 ended: Callable[[SceneHub, bool], None] = lambda hub, failed: None,
                 recordings: Recordings | None = None,
                 runners: RunnerFactory = SceneRunner) -> None:
        self.name = name
        self.members: dict[int, Connection] = {}  # joined, admitted or not yet
        self.connections: set[Connection] = set()  # admitted: they get every frame
        self.idle_since: float | None = time.monotonic()
        self.stored = store is not None  # its scene is kept on disk (and comes back from it)
        self.failed = False  # its process ended without being asked to
        self.refusal: VPError | None = None  # why it never started (a cluster with no room)
        self.heard = time.monotonic()  # when its process last sent anything (frames: 60 a second)
        self.asleep = False  # its process said it is idle (not ticking) and was sent nothing since
        self.figures: dict[str, Any] | None = None  # its last metrics, for when it is silent
        self.summary: dict[str, Any] | None = None  # its last counts, likewise
        self.saving: dict[str, Any] = {}  # what its process last said of its files
        self.viewer_frames = 0  # messages of its ticks, one per connection that got them
        self.fanout_cpu = 0.0  # CPU seconds this process spent handing them out
        self._owners, self._on_end, self._recordings = owners, ended, recordings
        self._open = asyncio.Event()  # made (restored), and no import under way
        self._imports = 0
        self._arriving = 0  # connections waiting for it to settle
        self.runner = runners(name, limits, tick_rate, assets, setup, self._events, store,
                                  recordings.folder if recordings is not None else None)

    @property
    def tick_rate(self) -> float:
        return self.runner.tick_rate

    @property
    def ended(self) -> bool:
        return self.runner.ended

    @property
    def silent(self) -> float:
        """Seconds since the scene's process last sent anything it owed: an idle scene
        (it said so, and was sent nothing since) owes nothing."""
        if self.asleep:  # silent since it was last asked something, if it was
            asked = self.runner.last_posted
            return time.monotonic() - asked if asked > self.heard else 0.0
        return time.monotonic() - self.heard

    @property
    def state(self) -> str:
        """``starting``, ``running``, ``unresponsive`` (silent for SILENT_SECONDS: stopped,
        or stuck in one long step), ``failed`` (its process died) or ``stopped``."""
        if self.ended:
            return "failed" if self.failed else "stopped"
        if not self._open.is_set() and not self._imports:
            return "starting"
        return "unresponsive" if self.silent > SILENT_SECONDS else "running"

    async def settled(self) -> None:
        """Wait until the scene is made and no import is under way: only then may a
        newcomer's client id be chosen (the owners it holds are reserved by then). The
        scene is not idle meanwhile (a slow start must not see it stopped)."""
        self._arriving += 1
        self.runner.expecting = True
        self.idle_since = None
        try:
            await self._open.wait()
        finally:
            self._arriving -= 1
            if not self.members and not self._arriving:
                self.idle_since = time.monotonic()  # join() says otherwise at once
        self._raise_if_ended()

    def _raise_if_ended(self) -> None:
        if self.ended:
            raise self.refusal or UnknownScene(f"scene {self.name} has ended", scene=self.name)

    @contextlib.asynccontextmanager
    async def importing(self) -> AsyncIterator[None]:
        """While the scene is replaced: newcomers wait (:meth:`settled`)."""
        await self.settled()
        self._imports += 1
        self._open.clear()
        try:
            yield
        finally:
            self._imports -= 1
            if not self._imports:
                self._open.set()

    def _events(self, events: list[Event]) -> None:
        self.heard = time.monotonic()
        for event in events:
            # asleep from Idle until the next event (a question's reply, answered without
            # waking it, is its runner's: never seen here)
            self.asleep = isinstance(event, Idle)
            match event:
                case Frame(items):
                    self.broadcast(items)
                case Answers(cid, items, applied):
                    self._answered(cid, items, applied)
                case Admit(cid, items):
                    self._admit(cid, items)
                case Saving(report):
                    self.saving = report
                case Ready(owners):
                    self._owners(owners)
                    if not self._imports:
                        self._open.set()
                case RecordingStarted(recording_id) if self._recordings is not None:
                    self._recordings.started(recording_id, self.name)
                case Recorded(summary) if self._recordings is not None:
                    self._recordings.ended(summary["id"])
                case Ended(failed, refusal):
                    self._ended(failed, refusal)
                case Idle() | RecordingStarted() | Recorded():
                    pass
                case _:
                    raise TypeError(f"not an event of a scene's process: {event!r}")

    def broadcast(self, items: list[Outgoing]) -> None:
        """Write a tick's messages to every connection (or queue them), counting the CPU
        it takes: the cost of a viewer, in ``/api/metrics``."""
        started = time.thread_time()
        connections = list(self.connections)
        if len(items) == 1:  # a tick's one frame: straight to every socket that keeps up
            frame = items[0].frame
            for connection in connections:
                direct = connection.direct
                if direct is None or not direct.write_now(frame):
                    connection.direct = None  # refused: queued (not asked again by send)
                    connection.send(items)
        else:
            for connection in connections:
                connection.send(items)
        self.viewer_frames += len(connections) * len(items)
        self.fanout_cpu += time.thread_time() - started

    async def join(self, connection: Connection) -> None:
        """Send a connection its hello and snapshot; it gets every later tick."""
        self._raise_if_ended()
        for other in list(self.members.values()):  # the same client back: the new one wins
            if other.client_id == connection.client_id:
                other.close_code, other.close_reason = REPLACED, \
                    f"replaced: client {other.client_id} connected again (resumed) elsewhere"
                other.shut()
        self.members[connection.number] = connection
        self.idle_since = None
        self.runner.post(Join(connection.number, connection.client_id, connection.role,
                              connection.resume, connection.keep, connection.trusted))
        await connection.admitted.wait()

    def _admit(self, number: int, items: list[Outgoing]) -> None:
        # in order with the frames: the snapshot is newer than every frame sent before it
        connection = self.members.get(number)
        if connection is None:
            return
        connection.send(items)
        if not connection.closed.is_set():
            self.connections.add(connection)
        connection.admitted.set()

    def leave(self, connection: Connection) -> None:
        """Forget a connection; its scene deletes what its client made."""
        self.connections.discard(connection)
        if self.members.pop(connection.number, None) is not None:
            self.runner.post(Leave(connection.number))
        if not self.members:
            self.idle_since = time.monotonic()

    def receive(self, connection: Connection, text: str | bytes) -> None:
        """Hand a client's text to the scene; its answers come back to it alone."""
        connection.inflight += len(text)
        if connection.inflight > INFLIGHT_BYTES:
            connection.drained.clear()
        self.runner.post(Text(connection.number, text))

    def _answered(self, number: int, answers: list[Outgoing], size: int) -> None:
        connection = self.members.get(number)
        if connection is not None:
            connection.send(answers)
            connection.applied(size)

    def _ended(self, failed: bool, refusal: VPError | None = None) -> None:
        """The scene's process is gone (or, ``refusal``, never started): its clients are
        disconnected (they may rejoin); those waiting for it are told why."""
        self.failed, self.refusal = failed, refusal
        self._open.set()  # whoever waits hears that it ended
        self._on_end(self, failed)
        for connection in self.members.values():
            if failed:
                connection.farewell = Outgoing.of((refusal or UnknownScene(
                    f"scene {self.name} failed and was closed; reconnect to start it "
                    f"again", scene=self.name)).to_wire())
            connection.shut()
            connection.admitted.set()
        self.connections.clear()
