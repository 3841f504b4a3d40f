"""The tick loop of each scene and the fan-out of its messages to every connection."""

from __future__ import annotations

import asyncio
import logging
import re
import time
from dataclasses import dataclass, field
from typing import Callable

from ..core.scene import Scene
from ..core.session import Session
from ..errors import LimitExceeded, OutOfRange
from .outbox import Outbox, Outgoing, SlowConsumer

log = logging.getLogger(__name__)

Animator = Callable[[Scene, float], None]
SCENE_NAME = re.compile(r"[A-Za-z0-9_-]{1,64}")
MAX_SCENES = 100


@dataclass(eq=False)
class Connection:
    """A client as the hub sees it: its session and its outbox."""

    session: Session
    outbox: Outbox = field(default_factory=Outbox)
    closed: asyncio.Event = field(default_factory=asyncio.Event)

    def send(self, item: Outgoing) -> None:
        """Queue a message; a connection that stopped reading is marked closed."""
        try:
            self.outbox.put(item)
        except SlowConsumer as reason:
            log.warning("closing %s: %s", self.session.client_id, reason)
            self.closed.set()


@dataclass
class TickStats:
    """How long ticks take, for /api/metrics."""

    count: int = 0
    last_ms: float = 0.0
    max_ms: float = 0.0
    total_ms: float = 0.0

    def add(self, ms: float) -> None:
        self.count += 1
        self.last_ms, self.total_ms = ms, self.total_ms + ms
        self.max_ms = max(self.max_ms, ms)


class SceneHub:
    """One scene, its connections and the task that ticks it at a fixed rate."""

    def __init__(self, scene: Scene, tick_rate: float) -> None:
        self.scene = scene
        self.tick_rate = tick_rate
        self.connections: set[Connection] = set()
        self.animators: list[Animator] = []
        self.stats = TickStats()
        self._task: asyncio.Task[None] | None = None

    def start(self) -> None:
        """Start ticking (needs a running event loop)."""
        self._task = asyncio.get_running_loop().create_task(self._run(), name=self.scene.name)

    async def stop(self) -> None:
        """Stop ticking and release the scene."""
        if self._task is not None:
            self._task.cancel()
            await asyncio.gather(self._task, return_exceptions=True)
        self.scene.close()

    def join(self, connection: Connection) -> None:
        """Send a connection its hello and snapshot; it gets every tick from now on."""
        connection.send(Outgoing.of(connection.session.hello(self.tick_rate)))
        connection.send(Outgoing.of(self.scene.snapshot()))
        self.connections.add(connection)

    def leave(self, connection: Connection) -> None:
        """Forget a connection and delete what its client made."""
        self.connections.discard(connection)
        connection.session.close()

    async def _run(self) -> None:
        loop = asyncio.get_running_loop()
        period = 1.0 / self.tick_rate
        last = deadline = loop.time()
        while True:
            deadline += period
            await asyncio.sleep(max(0.0, deadline - loop.time()))
            now = loop.time()
            if now - deadline > 5 * period:  # far behind (a paused process): do not race
                deadline = now
            try:
                self.tick(now - last)
            except Exception:
                log.exception("tick of scene %s failed", self.scene.name)
            last = now

    def tick(self, dt: float) -> None:
        """Run the animators, advance the scene and queue its messages for everyone."""
        started = time.perf_counter()
        for animate in self.animators:
            animate(self.scene, self.scene.time + dt)
        items = [Outgoing.of(message) for message in self.scene.tick(dt)]
        for connection in list(self.connections):
            for item in items:
                connection.send(item)
        self.stats.add((time.perf_counter() - started) * 1000)


class Hubs:
    """Every scene the server runs, by name; a scene is made on first use."""

    def __init__(self, tick_rate: float = 60.0) -> None:
        self.tick_rate = tick_rate
        self.scenes: dict[str, SceneHub] = {}
        self._clients = 0

    def get(self, name: str) -> SceneHub | None:
        """The hub of an existing scene."""
        return self.scenes.get(name)

    def open(self, name: str) -> SceneHub:
        """The hub of a scene, made and started if it does not exist yet."""
        hub = self.scenes.get(name)
        if hub is None:
            if not SCENE_NAME.fullmatch(name):
                raise OutOfRange(f"scene names are 1-64 letters, digits, _ or -; got {name!r}")
            if len(self.scenes) >= MAX_SCENES:
                raise LimitExceeded(f"the server runs the maximum of {MAX_SCENES} scenes")
            hub = self.scenes[name] = SceneHub(Scene(name), self.tick_rate)
            hub.start()
        return hub

    def new_client_id(self) -> str:
        """A fresh client id: c1, c2, …"""
        self._clients += 1
        return f"c{self._clients}"

    async def stop(self) -> None:
        """Stop every scene."""
        for hub in self.scenes.values():
            await hub.stop()
