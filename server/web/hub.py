"""The scenes a server runs, and the fan-out of each scene's messages to its connections.

Every method here runs on the event loop; the scenes themselves live on their runners'
threads (:mod:`server.web.runner`), which hand their messages back with
``call_soon_threadsafe``, so the loop sees them in the order they were made.
"""

from __future__ import annotations

import asyncio
import logging
import re
import time
from dataclasses import dataclass, field
from typing import Callable

from ..core.limits import DEFAULT, Limits
from ..core.scene import Scene
from ..core.session import Session
from ..errors import LimitExceeded, OutOfRange
from .outbox import Outbox, Outgoing, SlowConsumer
from .runner import Animator, SceneRunner

log = logging.getLogger(__name__)

SCENE_NAME = re.compile(r"[A-Za-z0-9_-]{1,64}")
DEFAULT_SCENE = "default"
INFLIGHT_BYTES = 4 << 20  # text a connection may have waiting on its scene's thread


@dataclass(eq=False)
class Connection:
    """A client as the loop sees it: its session, outbox, and text not yet applied."""

    session: Session
    outbox: Outbox
    closed: asyncio.Event = field(default_factory=asyncio.Event)
    inflight: int = 0
    drained: asyncio.Event = field(default_factory=asyncio.Event)

    def __post_init__(self) -> None:
        self.drained.set()

    def send(self, items: list[Outgoing]) -> None:
        """Queue messages; a connection that stopped reading is marked closed."""
        try:
            for item in items:
                self.outbox.put(item)
        except SlowConsumer as reason:
            if not self.closed.is_set():
                log.warning("closing %s: %s", self.session.client_id, reason)
            self.closed.set()

    def applied(self, size: int) -> None:
        """``size`` bytes of this connection's text were applied on the scene's thread."""
        self.inflight -= size
        if self.inflight <= INFLIGHT_BYTES:
            self.drained.set()


class SceneHub:
    """One scene: its runner (thread) and the connections that receive its messages."""

    def __init__(self, scene: Scene, tick_rate: float, loop: asyncio.AbstractEventLoop) -> None:
        self.scene = scene
        self.connections: set[Connection] = set()
        self.idle_since: float | None = time.monotonic()
        self._loop = loop
        self.runner = SceneRunner(scene, tick_rate, self._from_thread)

    @property
    def tick_rate(self) -> float:
        return self.runner.tick_rate

    def _from_thread(self, items: list[Outgoing]) -> None:
        try:
            self._loop.call_soon_threadsafe(self.broadcast, items)
        except RuntimeError:  # the loop closed while the scene was stopping
            pass

    def broadcast(self, items: list[Outgoing]) -> None:
        """Queue a tick's messages for every connection."""
        for connection in list(self.connections):
            connection.send(items)

    async def join(self, connection: Connection) -> None:
        """Send a connection its hello and snapshot; it gets every later tick."""
        session = connection.session

        def greet() -> None:
            items = [Outgoing.of(session.hello(self.tick_rate)), Outgoing.of(self.scene.snapshot())]
            self._loop.call_soon_threadsafe(self._admit, connection, items)
        self.idle_since = None
        await self.runner.call(greet)

    def _admit(self, connection: Connection, items: list[Outgoing]) -> None:
        # runs on the loop in order with the ticks: after every frame older than the snapshot
        connection.send(items)
        if not connection.closed.is_set():
            self.connections.add(connection)

    def leave(self, connection: Connection) -> None:
        """Forget a connection and, on the scene's thread, delete what its client made."""
        self.connections.discard(connection)
        self.runner.post(connection.session.close)
        if not self.connections:
            self.idle_since = time.monotonic()

    def receive(self, connection: Connection, text: str | bytes) -> None:
        """Apply a client's text on the scene's thread; its answers go back to it."""
        size = len(text)
        connection.inflight += size
        if connection.inflight > INFLIGHT_BYTES:
            connection.drained.clear()

        def apply() -> None:
            answers = [Outgoing.of(a) for a in connection.session.receive(text, time.monotonic())]
            self._loop.call_soon_threadsafe(self._answered, connection, answers, size)
        self.runner.post(apply)

    @staticmethod
    def _answered(connection: Connection, answers: list[Outgoing], size: int) -> None:
        connection.send(answers)
        connection.applied(size)


SceneSetup = Callable[[Scene], Animator | None]


class Hubs:
    """Every scene the server runs, by name; a scene is made on first use and removed
    when it has had no client for ``scene_idle_seconds`` (``default`` always stays)."""

    def __init__(self, tick_rate: float = 60.0, limits: Limits = DEFAULT) -> None:
        self.tick_rate = tick_rate
        self.limits = limits
        self.scenes: dict[str, SceneHub] = {}
        self.removed = 0
        self._clients = 0

    def get(self, name: str) -> SceneHub | None:
        """The hub of an existing scene."""
        return self.scenes.get(name)

    def open(self, name: str, setup: SceneSetup | None = None) -> SceneHub:
        """The hub of a scene, made and started if it does not exist yet."""
        hub = self.scenes.get(name)
        if hub is None:
            if not SCENE_NAME.fullmatch(name):
                raise OutOfRange(f"scene names are 1-64 letters, digits, _ or -; got {name!r}"
                                 if len(name) <= 80 else "scene names are 1-64 letters, "
                                 "digits, _ or -")
            if len(self.scenes) >= self.limits.scenes:
                raise LimitExceeded(f"the server runs the maximum of {self.limits.scenes} scenes",
                                    limit="scenes", value=self.limits.scenes)
            scene = Scene(name, self.limits)
            hub = self.scenes[name] = SceneHub(scene, self.tick_rate, asyncio.get_running_loop())
            if setup is not None:
                animator = setup(scene)
                if animator is not None:
                    hub.runner.animators.append(animator)
            hub.runner.start()
        return hub

    def new_client_id(self) -> str:
        """A fresh client id: c1, c2, … (never handed out twice by this server)."""
        self._clients += 1
        return f"c{self._clients}"

    def remove_idle(self, now: float) -> list[str]:
        """Stop the scenes that have had no client for the grace period; their names."""
        grace = self.limits.scene_idle_seconds
        idle = [name for name, hub in self.scenes.items() if name != DEFAULT_SCENE
                and not hub.connections and hub.idle_since is not None
                and now - hub.idle_since >= grace]
        for name in idle:
            self.scenes.pop(name).runner.stop()
            self.removed += 1
        return idle

    async def sweep(self) -> None:
        """Remove idle scenes, forever (a task of the server's lifetime)."""
        while True:
            await asyncio.sleep(min(5.0, self.limits.scene_idle_seconds / 2))
            for name in self.remove_idle(time.monotonic()):
                log.info("removed scene %s: no clients for %d s", name,
                         self.limits.scene_idle_seconds)

    async def stop(self) -> None:
        """Stop every scene."""
        for hub in self.scenes.values():
            hub.runner.stop()
        self.scenes.clear()
