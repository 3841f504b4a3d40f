"""A gateway: the server's WebSockets, REST and pages, its scenes run by workers.

:class:`Gateway` is what :class:`server.web.scenes.hub.Hubs` needs of the cluster: a
:data:`server.web.scenes.runner.RunnerFactory` making :class:`.remote_runner.RemoteRunner`\\ s,
client ids shared with the other gateways (:mod:`.client_ids`), one ordered sender for
everything the gateway publishes, and a heartbeat that tells each worker its attachments
live and notices when a worker has gone.
"""

from __future__ import annotations

import asyncio
import itertools
import logging
from collections import defaultdict
from pathlib import Path
from typing import Any

from ..core.kit.limits import Limits
from ..core.physics.assets import AssetLibrary
from ..core.kit.errors import BusUnavailable
from ..web.scenes.runner import Deliver
from ..web.storage.scene_store import SceneStore
from ..web.process.scene_start import SceneSetup
from .bus import LOADS, Bus, OrderedSender, ReturnAddress, Unanswered, alive_subject, gateway_subject
from .bus_messages import Attached
from .leases import break_worker, lease_holder
from .placement import Placement
from .remote_runner import RemoteRunner

log = logging.getLogger(__name__)
HEARTBEAT_SECONDS = 1.0
# a worker is gone after this many heartbeats in a row went to nobody (its connection to the
# bus is closed: it died); after this many unanswered, its leases decide (a swamped machine
# must not make its scenes hop from worker to worker)
MISSED_BEATS = {True: 2, False: 10}
# a bus away this long ends this gateway's attachments: their clients are told (REST 503,
# WS bus_unavailable) instead of waiting on answers the bus may never carry; after a
# shorter outage they end at its return (what crossed the bus as it went may be lost)
BUS_GRACE_SECONDS = 3.0


class Gateway:
    """This gateway's attachments to scenes, by worker."""

    def __init__(self, bus: Bus, name: str) -> None:
        self.bus, self.name = bus, name
        self._numbers = itertools.count(1)
        self._attached: dict[str, RemoteRunner] = {}
        self._missed: dict[str, int] = defaultdict(int)  # worker -> heartbeats unanswered
        self._outgoing = OrderedSender(bus)
        self._tasks: list[asyncio.Task[None]] = []
        self.placement = Placement(bus)

    async def place(self, attachment: str, scene: str,
                    expecting: bool) -> tuple[str, Attached] | None:
        return await self.placement.place(attachment, scene, expecting)

    def runner(self, name: str, limits: Limits, tick_rate: float, assets: AssetLibrary,
               setup: SceneSetup | None, deliver: Deliver, store: SceneStore | None,
               recordings: Path | None) -> RemoteRunner:
        """A scene's runner (the worker makes the scene with its own setups and store)."""
        return RemoteRunner(self, f"{self.name}-{next(self._numbers)}", name, tick_rate, deliver)

    async def start(self) -> None:
        """Answer workers that ask whether it lives; send; beat; survey the workers."""
        self.bus.link.returned.append(self._after_outage)
        await self.bus.subscribe(gateway_subject(self.name), self._alive)
        await self.bus.subscribe(LOADS, self.placement.told)
        self._tasks = [asyncio.create_task(self._outgoing.run()),
                       asyncio.create_task(self._beat()),
                       asyncio.create_task(self._watch_link()),
                       asyncio.create_task(self.placement.keep_surveying())]

    async def _alive(self, value: Any, reply: ReturnAddress | None) -> None:
        """A worker asks which of this gateway's attachments (``value``) it still holds."""
        if reply is not None:
            await reply.send([a for a in value or () if a in self._attached])

    def send(self, subject: str, value: Any) -> None:
        """Publish in order: one sender for every command of this gateway."""
        self._outgoing.send(subject, value)

    def attached(self, runner: RemoteRunner) -> None:
        self._attached[runner.attachment] = runner

    def detached(self, runner: RemoteRunner) -> None:
        self._attached.pop(runner.attachment, None)

    async def _beat(self) -> None:
        while True:
            await asyncio.sleep(HEARTBEAT_SECONDS)
            by_worker: dict[str, list[RemoteRunner]] = defaultdict(list)
            for runner in list(self._attached.values()):
                by_worker[runner.worker].append(runner)  # type: ignore[index]
            if self.bus.link.down_since is None:  # (a beat must not end the beating)
                outcomes = await asyncio.gather(*(self._check(worker, runners) for worker,
                                                  runners in by_worker.items()),
                                                return_exceptions=True)
                for outcome in outcomes:
                    if isinstance(outcome, Exception):
                        log.warning("heartbeat: %s", outcome or type(outcome).__name__)

    async def _watch_link(self) -> None:
        """End every attachment once the bus has been away BUS_GRACE_SECONDS."""
        while True:
            await asyncio.sleep(HEARTBEAT_SECONDS / 4)
            if self.bus.link.down_for >= BUS_GRACE_SECONDS and self._attached:
                self._end_all(self.bus.link.refusal("the scene cannot be reached"))

    def _after_outage(self) -> None:
        """The bus is back after an outage shorter than the grace: what crossed it meanwhile
        may be lost (a request sent as it went got no answer, ever), so the attachments
        end now too and their clients reconnect."""
        self._end_all(BusUnavailable(f"the cluster's bus at {self.bus.link.where} was away "
                                     f"for a moment: requests sent meanwhile may be lost; "
                                     f"reconnect", bus=self.bus.link.where))

    def _end_all(self, refusal: BusUnavailable) -> None:
        for runner in list(self._attached.values()):
            runner.lost(refusal)
        self._missed.clear()  # (no worker missed a beat: the bus did)

    async def _check(self, worker: str, runners: list[RemoteRunner]) -> None:
        try:
            alive = set(await self.bus.request(
                alive_subject(worker), [(r.attachment, r.name) for r in runners],
                HEARTBEAT_SECONDS))
        except Unanswered as unanswered:
            self._missed[worker] += 1
            if self._missed[worker] >= MISSED_BEATS[unanswered.gone]:
                del self._missed[worker]
                await self._unanswered(worker, runners, unanswered.gone)
            return
        self._missed.pop(worker, None)
        for runner in runners:
            if runner.attachment not in alive:
                log.warning("worker %s no longer runs scene %s for %s", worker, runner.name,
                            runner.attachment)
                runner.lost()

    async def _unanswered(self, worker: str, runners: list[RemoteRunner], gone: bool) -> None:
        """A worker that left the bus has died: its scenes start elsewhere at once. One that
        only does not answer (swamped, or stuck) keeps the scenes it still holds the lease
        of; those it does not hold any more are lost."""
        if gone:
            await break_worker(self.bus.workers, worker)
        for runner in runners:
            if gone or await lease_holder(self.bus.workers, self.bus.scenes,
                                          runner.name) != worker:
                runner.lost()
            else:
                log.warning("worker %s has not answered for %d s; it still holds scene %s",
                            worker, MISSED_BEATS[False], runner.name)

    async def stop(self) -> None:
        await self._outgoing.flush()  # the detachments of the scenes just stopped
        for task in self._tasks:
            task.cancel()
