"""A gateway's handle on a scene a worker runs: :class:`server.web.scenes.runner.Runner` over the bus.

It places the scene first (the worker holding its lease, else the least busy one that
claims it; while a dead worker's lease lapses it keeps trying), then sends commands in
the order they were posted (those posted meanwhile wait) and hands the scene's events to
its hub, as :class:`server.web.scenes.runner.SceneRunner` does for a process of its own. It ends
when it is detached (asked to stop), when the scene's process ends, or when its worker
stops answering (:class:`.gateway.Gateway`'s heartbeat): then as a failed scene, which its
clients reconnect to, and it starts again elsewhere.
"""

from __future__ import annotations

import asyncio
from collections import deque
import logging
import threading
import time
from typing import Any, Protocol

from ..core.kit.errors import UnknownScene, VPError
from ..web.process.messages import (Command, Detach, Detached, Ended, Event, Idle, Question,
                                    Ready, Reply, Saving)
from ..web.scenes.runner import Deliver, Replies, Runner
from .bus import Bus, commands_subject, events_subject
from .bus_messages import Attached, SceneCommands, SceneEvents

log = logging.getLogger(__name__)
PLACE_SECONDS = 30.0  # how long a scene waits for a worker (a dead one's lease lapses sooner)
RETRY_SECONDS = 0.25
EARLY_EVENTS = 1024


class Attachments(Protocol):
    """What a runner needs of its gateway (:class:`.gateway.Gateway`)."""

    bus: Bus

    def send(self, subject: str, value: Any) -> None:
        """Publish, in order with everything else the gateway sends."""

    async def place(self, attachment: str, scene: str,
                    expecting: bool) -> tuple[str, Attached] | None:
        """Attach to the scene's worker (placing the scene first if it runs nowhere;
        ``expecting``: a client waits for it): the worker and its answer, or None for
        "not yet"."""

    def attached(self, runner: RemoteRunner) -> None:
        """The runner is placed: its worker's heartbeat covers it now."""

    def detached(self, runner: RemoteRunner) -> None:
        """The runner has ended."""


class RemoteRunner:
    """One attachment: this gateway's handle on a scene some worker runs."""

    def __init__(self, gateway: Attachments, attachment: str, name: str, tick_rate: float,
                 deliver: Deliver) -> None:
        self.gateway, self.attachment, self.name = gateway, attachment, name
        self.tick_rate = tick_rate
        self.worker: str | None = None
        self.last_posted = 0.0
        self.ended = False
        self.stopping = False
        self.expecting = False  # a client waits for the scene: its worker counts it at once
        self._deliver = deliver
        self._waiting: list[Command] = []  # posted before it was placed
        self._replies = Replies()
        self._events: Any = None  # the subscription to the scene's events
        self._placing: asyncio.Task[None] | None = None
        self._incarnation: str | None = None  # the scene's process on its worker, once placed
        # its events heard before the worker's answer (frames of a scene running already:
        # the newest are enough; only those after the answer was made matter)
        self._early: deque[SceneEvents] = deque(maxlen=EARLY_EVENTS)
        self._gone = threading.Event()  # join() waits in a thread
        self._pid: int | None = None

    @property
    def pid(self) -> int | None:
        """The scene's process id, on its worker."""
        return self._pid

    @property
    def unsaved(self) -> bool:
        """Never here: a scene's saving is its worker's (``vp-server --role worker``'s exit code)."""
        return False

    def start(self, after: Runner | None = None) -> None:
        """Place the scene. A predecessor still stopping (``after``) is its worker's to
        wait for: the scene's lease is still that worker's, so it is placed there again."""
        self._placing = asyncio.create_task(self._place())

    async def _place(self) -> None:
        link = self.gateway.bus.link
        try:
            link.check(f"scene {self.name} cannot start")
            self._events = await self.gateway.bus.subscribe(events_subject(self.name),
                                                            self._receive)
            deadline = time.monotonic() + PLACE_SECONDS
            while (placed := await self.gateway.place(self.attachment, self.name,
                                                             self.expecting)) is None:
                if time.monotonic() > deadline:
                    raise UnknownScene(f"no worker took scene {self.name} within "
                                       f"{PLACE_SECONDS:.0f} s: none answered, or each is "
                                       f"full (--limit scenes, --worker-cores)",
                                       scene=self.name)
                await asyncio.sleep(RETRY_SECONDS)
        except asyncio.CancelledError:
            raise
        except VPError as error:  # refused (every worker full) or none answered in time
            log.warning("scene %s could not be placed: %s", self.name, error.message)
            self._end(True, error)
            return
        except Exception as error:  # the bus failed us: the scene fails; a client's return retries
            if link.down_since is None:
                log.exception("scene %s could not be placed", self.name)
                self._end(True)
            else:
                log.warning("scene %s could not be placed: %s", self.name, error)
                self._end(True, link.refusal(f"scene {self.name} cannot start"))
            return
        self.worker, answer = placed
        self._pid, self._incarnation = answer.pid, answer.incarnation
        self.gateway.attached(self)
        if answer.ready is not None:  # made before this attachment: it will not say so again
            self._deliver([Ready(answer.ready)])
        if answer.saving:
            self._deliver([Saving(answer.saving)])
        if answer.asleep:  # it ticks no more until sent something: silent, not stuck
            self._deliver([Idle()])
        early, self._early = list(self._early), deque()
        for message in early:
            self._receive(message, None)
        self.gateway.send(commands_subject(self.worker, self.name),
                          SceneCommands(self.attachment, self._waiting))
        self._waiting = []

    def post(self, command: Command) -> None:
        """Send a command; the scene applies a gateway's commands in the order posted."""
        self.last_posted = time.monotonic()
        if self.worker is None:
            self._waiting.append(command)
        else:
            self.gateway.send(commands_subject(self.worker, self.name),
                              SceneCommands(self.attachment, [command]))

    def call(self, question: Question) -> asyncio.Future[Any]:
        """Send a command that is answered; its reply, awaitable."""
        link = self.gateway.bus.link
        refusal = UnknownScene(f"scene {self.name} has ended", scene=self.name) if self.ended \
            else link.refusal(f"scene {self.name}") if link.down_since is not None else None
        return self._replies.ask(self.post, question, refusal)

    def stop(self) -> None:
        """Detach: the worker stops the scene when no other gateway is attached to it."""
        self.stopping = True
        if self.worker is None and self._placing is not None:
            self._placing.cancel()
            self._end(False)
        elif not self.ended:
            self.post(Detach())

    def join(self, timeout: float) -> None:
        """Wait until detached (the scene saved, if it stopped)."""
        self._gone.wait(timeout)

    def _receive(self, message: SceneEvents, reply: Any) -> None:
        if self._incarnation is None:
            self._early.append(message)
            return
        if message.incarnation != self._incarnation or self.ended:
            return  # a predecessor's last words, or after the end
        mine: list[Event] = []
        for addressed in message.events:
            if addressed.attachment not in (None, self.attachment):
                continue
            match addressed.event:
                case Reply() as reply_event:
                    self._replies.answer(reply_event)
                case Detached():
                    self._end(False)
                    return
                case Ended(failed):
                    self._end(failed and not self.stopping)
                    return
                case event:
                    mine.append(event)
        if mine and not self.ended:
            self._deliver(mine)

    def lost(self, why: VPError | None = None) -> None:
        """Its worker stopped answering, or (``why``) the bus is away: the scene failed
        here (it starts again, elsewhere if its worker is gone)."""
        if why is None:
            log.error("the worker %s of scene %s stopped answering", self.worker, self.name)
        self._end(not self.stopping, why)

    def _end(self, failed: bool, refusal: VPError | None = None) -> None:
        """The scene ends here (``refusal``: why it never started, for its waiting clients)."""
        if self.ended:
            return
        self.ended = True
        self.gateway.detached(self)
        if self._events is not None:
            asyncio.create_task(self._events.unsubscribe())
        self._replies.fail(self.name, refusal)
        self._deliver([Ended(failed, refusal)])
        self._gone.set()
