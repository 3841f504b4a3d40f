"""A worker: runs scenes for the cluster's gateways (``vp-server --role worker``).

Each scene is a process of :mod:`server.web.scenes.runner`, as on a single server; the worker
holds its lease (:mod:`.leases`), takes its commands from the bus and publishes its events
once, for every gateway attached to it (:mod:`.bus`). An *attachment* is one gateway's
handle on one scene (:class:`.remote_runner.RemoteRunner`); a client connection is named
by its attachment and the gateway's number for it, so connections of different gateways
never collide. A scene stops when its last attachment detaches (the gateway found it idle),
or, once every gateway attached to it has gone silent, when it has been alone for
``sceneIdleSeconds`` and holds nothing or is saved.
"""

from __future__ import annotations

import asyncio
import itertools
import json
import logging
import time
from dataclasses import replace
from typing import Any, Mapping

from ..core.kit.limits import Limits
from ..core.physics.assets import AssetLibrary
from ..web.scenes.hub import clients_objects
from ..web.scenes.runner import SceneRunner
from ..web.storage.state_dir import StateDir
from ..web.process.scene_start import SceneSetup
from ..web.process.messages import (Admit, Answers, Ask, Command, Detach, Detached, Ended,
                                    Event, Idle, Join, Leave, Read, Ready, Reply, Saving, Text)
from .bus import (LOADS, PLACE, Bus, OrderedSender, ReturnAddress, Unanswered,
                  alive_subject, attach_subject, commands_subject, events_subject, gateway_of,
                  gateway_subject)
from .bus_messages import (Addressed, Attach, AttachAnswer, Attached, Elsewhere, Full, Load,
                           NoRoom, SceneCommands, SceneEvents)
from .leases import Leases
from .process_cpu import ProcessCpu

log = logging.getLogger(__name__)
# Scenes run below the worker's own priority: when they want more than the cores give, the
# worker still renews its lease and answers (else its scenes would hop to other workers)
SCENE_NICE = 5
CPU_SHARE = 0.8  # of its cores, the most its scenes' processes use before it takes no more
# what a scene not measured yet is expected to use, at least: a scene with a hand moving
# takes about 0.04 of a core here (bench/RESULTS.md), so a burst of placements within one
# measure (each second) stops near the bound rather than far past it
NEW_SCENE_CORES = 0.05
# a gateway not heard of this long (its heartbeat comes each second) is asked whether it
# lives: one that has left the bus (died) loses its attachments; a swamped one keeps them
SILENT_SECONDS = 5.0
# a scene placed for a client that has not joined yet counts as attended this long (on a
# loaded machine a survey came between a placement and its client's joining); one placed
# with no client waiting (a gateway's default scene, a REST read) does not
JOINING_SECONDS = 30.0


class HostedScene:
    """One scene this worker runs: its process, attachments and their connections."""

    def __init__(self, host: WorkerHost, name: str, incarnation: str,
                 after: SceneRunner | None) -> None:
        self.host, self.name = host, name
        self.incarnation = incarnation  # its events carry it: a predecessor's are told apart
        self.heard: dict[str, float] = {}  # attachment -> when it was last heard of
        self.connections: dict[str, set[int]] = {}  # attachment -> its connections' numbers
        self.alone_since: float | None = None
        self.joining_until: float | None = None  # (expected until then, not joined yet)
        self.owners: list[str] | None = None  # from "ready": the scene is made
        self.asleep = False  # it last said "idle": a newcomer must not take silence for death
        self.saving: dict[str, Any] = {}
        self.subscription: Any = None
        self.runner = SceneRunner(name, host.limits, host.tick_rate, host.assets,
                                  host.setups.get(name), self._deliver,
                                  host.state.store(name) if host.state is not None else None,
                                  host.state.root / "recordings" if host.state is not None else None,
                                  nice=SCENE_NICE)
        self.runner.start(after)

    def attach(self, attachment: str, expecting: bool) -> Attached:
        self.heard[attachment] = time.monotonic()
        if expecting and not any(self.connections.values()):
            self.joining_until = time.monotonic() + JOINING_SECONDS
        self.connections.setdefault(attachment, set())
        self.alone_since = None
        return Attached(self.runner.pid, self.incarnation, self.owners, self.saving, self.asleep,
                        self.host.load())  # (this scene included)

    def attended(self) -> bool:
        """Whether a client uses the scene, or is about to (made for it, not joined yet)."""
        joining = self.joining_until is not None and time.monotonic() < self.joining_until
        return joining or any(self.connections.values())

    def command(self, batch: SceneCommands) -> None:
        """A gateway's commands, in the order it sent them."""
        attachment = batch.attachment
        if attachment not in self.heard:
            return  # detached, or silent too long: its clients have left
        self.heard[attachment] = time.monotonic()
        for command in batch.commands:
            self._command(attachment, command)

    def _command(self, attachment: str, command: Command) -> None:
        match command:
            case Ask(number, question):
                self.runner.call(question).add_done_callback(
                    lambda done: self._answer(attachment, number, done))
            case Detach():
                self.detach(attachment)
            case Join(cid):
                self.connections[attachment].add(cid)  # type: ignore[arg-type]
                self.joining_until = None
                self._post(attachment, command)
            case Leave(cid):
                self.connections[attachment].discard(cid)  # type: ignore[arg-type]
                self.host.tell_load()
                self._post(attachment, command)
            case Text():
                self._post(attachment, command)
            case _:
                raise TypeError(f"not a command a gateway sends: {command!r}")

    def _post(self, attachment: str, command: Join | Text | Leave) -> None:
        """A connection's command, the connection named by its attachment here: connections
        of different gateways never collide."""
        self.runner.post(replace(command, cid=(attachment, command.cid)))

    def _answer(self, attachment: str, number: int, done: asyncio.Future[Any]) -> None:
        failure = done.exception()
        self._publish([Addressed(attachment, Reply(number, failure is None,
                                                   failure if failure is not None
                                                   else done.result()))])

    def _publish(self, events: list[Addressed]) -> None:
        self.host.publish(events_subject(self.name), SceneEvents(self.incarnation, events))

    def detach(self, attachment: str) -> None:
        """The attachment is gone: its clients leave; the scene stops when none is left and
        the attachment asked (it found the scene idle), else it waits (``alone_since``)."""
        for cid in self.connections.pop(attachment, ()):
            self.runner.post(Leave((attachment, cid)))
        asked = self.heard.pop(attachment, None) is not None
        self.host.tell_load()
        if not self.heard:
            self.alone_since = time.monotonic()
            if asked:
                self.runner.stop()
        self._publish([Addressed(attachment, Detached())])

    def _deliver(self, events: list[Event]) -> None:
        routed = []
        for event in events:
            match event:
                case Admit((attachment, number)) | Answers((attachment, number)):
                    # a connection's: its attachment's alone, as the gateway numbered it
                    routed.append(Addressed(attachment, replace(event, cid=number)))
                    continue
                case Ready(owners):
                    self.owners = owners
                case Saving(report):
                    self.saving = report
            if not isinstance(event, Reply):
                self.asleep = isinstance(event, Idle)
            routed.append(Addressed(None, event))
        self._publish(routed)
        if isinstance(events[-1], Ended):
            self.host.ended(self)


class WorkerHost:
    """The scenes one worker runs, placed on it through the bus."""

    def __init__(self, bus: Bus, name: str, limits: Limits, tick_rate: float,
                 assets: AssetLibrary, setups: Mapping[str, SceneSetup],
                 state: StateDir | None, cores: float) -> None:
        self.bus, self.name = bus, name
        self.limits, self.tick_rate, self.assets, self.setups = limits, tick_rate, assets, setups
        self.state = state
        self.cores = cores  # its share of the machine (--worker-cores)
        self.cpu = ProcessCpu()
        self.scenes: dict[str, HostedScene] = {}
        self.leases = Leases(bus.workers, bus.scenes, name)
        self._incarnations = itertools.count(1)
        self._claims = asyncio.Lock()  # one placement at a time: a scene is started once
        self._outgoing = OrderedSender(bus)
        self._tasks: list[asyncio.Task[None]] = []

    async def start(self) -> None:
        """Answer placements and heartbeats; renew leases; look after silent attachments."""
        await self.leases.start()
        self.bus.link.returned.append(lambda: self._later(self._renew_once()))
        await self.bus.subscribe(PLACE, self._load)
        await self.bus.subscribe(attach_subject(self.name), self._attach)
        await self.bus.subscribe(alive_subject(self.name), self._alive)
        self._tasks = [asyncio.create_task(self._outgoing.run()),
                       asyncio.create_task(self._renew()),
                       asyncio.create_task(self._sweep())]
        log.info("worker %s runs scenes for the cluster", self.name)

    def publish(self, subject: str, value: Any) -> None:
        """Publish in order (one sender for everything this worker says)."""
        self._outgoing.send(subject, value)

    async def _load(self, value: Any, reply: ReturnAddress | None) -> None:
        if reply is not None:
            await reply.send(self.load())

    def load(self) -> Load:
        """How busy this worker is now (what gateways place scenes by)."""
        return Load(self.name, self.attended(), self.room(), time.monotonic())

    def tell_load(self) -> None:
        """Tell every gateway when a scene may be attended no more (a client left, a scene
        ended): a gateway that placed here counted it until its next survey, and a
        Gymnasium vector's scenes, placed at once after its probe environment left, went
        to one worker."""
        self.publish(LOADS, self.load())

    def attended(self) -> int:
        """How busy this worker is, as gateways place scenes by it: its scenes with a client
        or made for one not joined yet (:meth:`HostedScene.attended`). A scene its clients
        have left stops once idle; counted, it sent the next scenes
        elsewhere (Gymnasium's vector environment makes one environment to read its spaces
        and closes it: both of the vector's scenes then went to the other worker)."""
        return sum(1 for hosted in self.scenes.values() if hosted.attended())

    def room(self) -> NoRoom | None:
        """Why this worker takes no more scenes (None: it has room). Besides the ``scenes``
        limit, its scenes' processes must leave some of its cores free: past that a new
        scene would only slow every other, and this worker's own work (renewing its lease,
        answering) would starve."""
        if len(self.scenes) >= self.limits.scenes:
            return NoRoom("scenes", self.limits.scenes, "--limit scenes=N",
                          f"it runs its maximum of {self.limits.scenes} scenes")
        pids = [hosted.runner.pid for hosted in self.scenes.values()]
        # a new scene is expected to use what attended ones do: one its client has left
        # had its start's burst measured (a Gymnasium vector's probe environment: as much
        # again for the next scene, and the worker was full for both of the vector's)
        attended = [hosted.runner.pid for hosted in self.scenes.values()
                    if hosted.attended() and hosted.runner.pid is not None]
        expected = self.cpu.expected(pids + [None], NEW_SCENE_CORES, attended)  # (one more)
        if expected > CPU_SHARE * self.cores:
            return NoRoom("workerCores", self.cores, "--worker-cores",
                          f"its {len(pids)} scenes and one more would use {expected:.2f} of "
                          f"its {self.cores:g} cores, more than {CPU_SHARE:.0%}")
        return None

    async def _attach(self, asked: Attach, reply: ReturnAddress | None) -> None:
        async with self._claims:
            answer = await self._place(asked.attachment, asked.scene, asked.expecting)
        if reply is not None:
            await reply.send(answer)

    async def _place(self, attachment: str, scene: str, expecting: bool) -> AttachAnswer:
        hosted = self.scenes.get(scene)
        if hosted is not None and not hosted.runner.stopping:
            return hosted.attach(attachment, expecting)
        if hosted is None and self.room() is not None:
            return Full(self.load())
        holder = await self.leases.claim(scene)
        if holder is not None:
            return Elsewhere(holder)
        # (a predecessor still stopping: its last save is what the new process restores)
        after = hosted.runner if hosted is not None else None
        hosted = self.scenes[scene] = HostedScene(self, scene,
                                                  f"{self.name}.{next(self._incarnations)}", after)
        hosted.subscription = await self.bus.subscribe(
            commands_subject(self.name, scene),
            lambda batch, reply, hosted=hosted: hosted.command(batch))
        return hosted.attach(attachment, expecting)

    async def _alive(self, value: Any, reply: ReturnAddress | None) -> None:
        """A gateway's heartbeat for its attachments here; the ones still running."""
        now, alive = time.monotonic(), []
        for attachment, scene in value:
            hosted = self.scenes.get(scene)
            if hosted is not None and attachment in hosted.heard and not hosted.runner.ended:
                hosted.heard[attachment] = now
                alive.append(attachment)
        if reply is not None:
            await reply.send(alive)

    def ended(self, hosted: HostedScene) -> None:
        """A scene's process ended: its lease goes, unless a new process runs it already."""
        if self.scenes.get(hosted.name) is hosted:
            del self.scenes[hosted.name]
            asyncio.create_task(self.leases.release(hosted.name))
            self.tell_load()
        if hosted.subscription is not None:
            asyncio.create_task(hosted.subscription.unsubscribe())

    async def _renew(self) -> None:
        while True:
            # (the bus's lease, which the first process to use the bus set, not this one's flag)
            await asyncio.sleep(self.bus.lease_seconds / 5)
            if self.bus.link.down_since is None:
                await self._renew_once()

    async def _renew_once(self) -> None:
        """Write this worker's key again (at once when the bus comes back: its key may have
        lapsed meanwhile, and gateways place scenes as soon as they can)."""
        try:
            lost = await self.leases.renew()
        except Exception as error:  # the bus is slow or away: the leases last a while
            log.warning("leases not renewed: %s", error or type(error).__name__)
            return
        for scene in lost:  # another worker runs it now: this copy must not save over it
            hosted = self.scenes.pop(scene, None)
            if hosted is not None:
                log.error("scene %s stops unsaved here: another worker runs it", scene)
                hosted.runner.kill()

    def _later(self, work: Any) -> None:
        task = asyncio.create_task(work)
        self._tasks.append(task)
        task.add_done_callback(self._tasks.remove)

    async def _sweep(self) -> None:
        while True:
            await asyncio.sleep(1.0)
            self.cpu.measure([h.runner.pid for h in self.scenes.values() if h.runner.pid])
            try:
                await self._sweep_once(time.monotonic())
            except Exception as error:  # (the bus went away meanwhile: the next sweep)
                log.warning("sweeping the scenes: %s", error or type(error).__name__)

    async def _sweep_once(self, now: float) -> None:
        """Detach what silent gateways no longer hold; stop scenes idle past the grace."""
        link = self.bus.link
        # (just back from an outage, every attachment is silent: gateways beat again first)
        if link.down_since is None and now - link.up_since > SILENT_SECONDS:
            await self._forget_silent(now)
        for hosted in list(self.scenes.values()):
            if hosted.alone_since is not None and not hosted.runner.stopping and \
                    now - hosted.alone_since >= self.limits.scene_idle_seconds:
                await self._stop_if_idle(hosted)

    async def _forget_silent(self, now: float) -> None:
        """Attachments not heard of for SILENT_SECONDS whose gateway has left the bus (died)
        or no longer holds them (it ended them while the bus was away) are detached."""
        silent: dict[str, set[str]] = {}
        for hosted in self.scenes.values():
            for attachment, heard in hosted.heard.items():
                if now - heard > SILENT_SECONDS:
                    silent.setdefault(gateway_of(attachment), set()).add(attachment)
        held = await asyncio.gather(*(self._held(g, a) for g, a in silent.items()))
        dropped = set().union(*(a - h for a, h in zip(silent.values(), held)))
        for hosted in list(self.scenes.values()):
            for attachment in [a for a in hosted.heard if a in dropped]:
                log.warning("gateway %s no longer holds %s: scene %s loses its clients there",
                            gateway_of(attachment), attachment, hosted.name)
                hosted.heard.pop(attachment)
                hosted.detach(attachment)

    async def _held(self, gateway: str, attachments: set[str]) -> set[str]:
        """Which of ``attachments`` a gateway silent a while still holds: none when it has
        left the bus (died); all when it does not answer (it is only swamped)."""
        try:
            return set(await self.bus.request(gateway_subject(gateway), sorted(attachments),
                                              SILENT_SECONDS))
        except Unanswered as unanswered:
            return set() if unanswered.gone else attachments

    async def _stop_if_idle(self, hosted: HostedScene) -> None:
        """Stop a scene no gateway has attached to for the grace period, unless it holds
        objects it would lose (it is not saved)."""
        if self.state is None:  # not saved: what it holds would be lost
            held = json.loads(await hosted.runner.call(Read(clients_objects)))
            if held:
                return
        if hosted.alone_since is not None and not hosted.heard:
            hosted.runner.stop()

    async def stop(self) -> list[str]:
        """Stop every scene (each saved first); the scenes whose last changes could not be saved."""
        for task in list(self._tasks):
            task.cancel()
        runners = [hosted.runner for hosted in self.scenes.values()]
        for runner in runners:
            runner.stop()
        await asyncio.to_thread(lambda: [runner.join(10) for runner in runners])
        for scene in list(self.scenes):
            await self.leases.release(scene)
        await self._outgoing.flush()  # the scenes' last words
        return sorted(runner.name for runner in runners if runner.unsaved)
