"""One scene on a thread of its own: its requests, ticks and reads happen there, in order.

The event loop only moves bytes. Everything that touches a scene (decoding and applying
messages, ticking, encoding frames, REST reads) runs on the scene's thread, so a scene
flooded with work delays its own frames but never the event loop or another scene.
PyBullet holds the GIL while it works, which is why its calls are bounded elsewhere
(:mod:`server.core.contacts`); between them Python switches threads every millisecond.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import logging
import queue
import sys
import threading
import time
from collections import deque
from dataclasses import dataclass, field
from typing import Any, Callable, TypeVar

from ..core.scene import Scene
from ..errors import UnknownScene
from .outbox import Outgoing

log = logging.getLogger(__name__)
T = TypeVar("T")
Animator = Callable[[Scene, float], None]
Broadcast = Callable[[list[Outgoing]], None]
_STOP = object()
SWITCH_INTERVAL = 0.001  # seconds a thread may hold the GIL while another waits

sys.setswitchinterval(SWITCH_INTERVAL)


@dataclass
class TickStats:
    """How long recent ticks took (a window of the last 600), for /api/metrics."""

    count: int = 0
    failures: int = 0
    recent: deque[float] = field(default_factory=lambda: deque(maxlen=600))

    def add(self, ms: float) -> None:
        self.count += 1
        self.recent.append(ms)

    def summary(self) -> dict[str, float]:
        """Last, mean and max tick duration over the window, in milliseconds."""
        recent = list(self.recent) or [0.0]
        return {"tickMsLast": recent[-1], "tickMsMean": sum(recent) / len(recent),
                "tickMsMax": max(recent)}


class SceneRunner:
    """The thread of one scene: jobs in arrival order, and a tick whenever one is due."""

    def __init__(self, scene: Scene, tick_rate: float, broadcast: Broadcast) -> None:
        self.scene = scene
        self.tick_rate = tick_rate
        self.animators: list[Animator] = []
        self.stats = TickStats()
        self._broadcast = broadcast
        self._jobs: queue.SimpleQueue[Any] = queue.SimpleQueue()
        self._resync = False
        self._thread = threading.Thread(target=self._run, name=f"scene-{scene.name}",
                                        daemon=True)

    def start(self) -> None:
        """Start the scene's thread."""
        self._thread.start()

    def stop(self) -> None:
        """Finish the jobs queued so far, stop, and release the scene."""
        self._jobs.put(_STOP)
        self._thread.join(timeout=10)

    def post(self, job: Callable[[], None]) -> None:
        """Run ``job`` on the scene's thread after every job posted before it."""
        self._jobs.put(job)

    def call(self, job: Callable[[], T]) -> asyncio.Future[T]:
        """Run ``job`` on the scene's thread; its result (or exception) for the event loop."""
        future: concurrent.futures.Future[T] = concurrent.futures.Future()
        if not self._thread.is_alive():
            future.set_exception(UnknownScene(f"scene {self.scene.name} was removed",
                                              scene=self.scene.name))
            return asyncio.wrap_future(future)

        def run() -> None:
            if future.set_running_or_notify_cancel():
                try:
                    future.set_result(job())
                except BaseException as error:  # handed to whoever awaits it
                    future.set_exception(error)
        self._jobs.put(run)
        return asyncio.wrap_future(future)

    def _run(self) -> None:
        period = 1.0 / self.tick_rate
        last = deadline = time.monotonic()
        try:
            while True:
                wait = deadline - time.monotonic()
                if wait <= 0:
                    now = time.monotonic()
                    self._tick(now - last)
                    last, deadline = now, max(deadline + period, now - 5 * period)
                    continue
                try:
                    job = self._jobs.get(timeout=wait)
                except queue.Empty:
                    continue
                if job is _STOP:
                    return
                try:
                    job()
                except Exception:  # a bug in a job must not stop the scene
                    log.exception("job of scene %s failed", self.scene.name)
        finally:
            self.scene.close()

    def _tick(self, dt: float) -> None:
        """Run the animators, advance the scene and hand its encoded messages out."""
        started = time.perf_counter()
        try:
            for animate in self.animators:
                animate(self.scene, self.scene.time + dt)
            items = self._resynced() + [Outgoing.of(m) for m in self.scene.tick(dt)]
        except Exception:  # the scene kept what it had not sent; viewers resync later
            self.stats.failures += 1
            self._resync = True
            log.exception("tick of scene %s failed", self.scene.name)
            return
        self._broadcast(items)
        self.stats.add((time.perf_counter() - started) * 1000)

    def _resynced(self) -> list[Outgoing]:
        """After a failed tick, a fresh snapshot first: every client rebuilds from it."""
        if not self._resync:
            return []
        snapshot = Outgoing.of(self.scene.snapshot())
        self._resync = False
        return [snapshot]
