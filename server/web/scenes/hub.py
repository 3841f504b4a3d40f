"""The scenes a server runs, by name: made on first use, stopped when idle, started again
when they fail (the server's own), and the client ids handed out to their connections.

Every method here runs on the event loop; each scene is a :class:`SceneHub`.
"""

from __future__ import annotations

import asyncio
import hashlib
import hmac
import json
import logging
import re
import time
from typing import Any, Callable

from ...core.kit.ids import owner_of
from ...core.kit.limits import DEFAULT, Limits
from ...core.physics.assets import AssetLibrary
from ...core.protocol.scene_document import uploaded_assets
from ...core.scene.scene import Scene
from ...core.kit.errors import LimitExceeded, OutOfRange, UnknownScene, VPError
from ..process import heap
from ..connections.client_ids import ClientIdSource, ClientIds
from .offload import Offload
from .runner import PREDECESSOR_SECONDS, Runner, RunnerFactory, SceneRunner
from .scene_hub import SceneHub
from ..recording.recordings import Recordings
from ..storage.scene_store import SceneStore
from ..storage.upload_folder import UploadFolder
from ..storage.state_dir import SCENE_NAME, StateDir
from ..process.messages import Read
from ..process.scene_start import SERVER_OWNER, SceneSetup

__all__ = ["DEFAULT_SCENE", "Hubs", "SceneSetup"]

log = logging.getLogger(__name__)
BESIDE_NICE = 10  # how far below the scenes exports, replays and resimulations run

CLIENT_ID = re.compile(r"c[0-9]{1,15}")
DEFAULT_SCENE = "default"
RESTART_SECONDS = (1.0, 60.0)  # a failed setup scene starts again after 1 s, doubling to 60 s


def _saved_asset_names(stores: list[SceneStore]) -> set[str]:
    """The uploaded files saved documents name (read in the checking process)."""
    return set().union(*(store.asset_names() for store in stores))


def clients_objects(scene: Scene) -> int:
    """How many objects clients have in a scene (read in its process); the server's own
    come back with the scene's setup."""
    return sum(owner_of(node_id) != SERVER_OWNER for node_id in scene.nodes)


class Hubs:
    """Every scene the server runs, by name; a scene is made on first use and removed
    when it has had no client for ``scene_idle_seconds`` (``default`` always stays) and
    holds nothing, or holds what is kept in ``state`` (then it comes back from there)."""

    def __init__(self, tick_rate: float = 60.0, limits: Limits = DEFAULT,
                 assets: AssetLibrary | None = None, state: StateDir | None = None,
                 runners: RunnerFactory = SceneRunner, ids: ClientIdSource | None = None) -> None:
        self.tick_rate = tick_rate
        self.limits = limits
        self.assets = assets or AssetLibrary()  # every scene reads uploads through it
        self.uploads = UploadFolder(self.assets)  # uploads are kept in its folder
        self.state = state
        self.scenes: dict[str, SceneHub] = {}
        self._stopping: dict[str, Runner] = {}  # removed scenes whose process may run on
        self.removed = 0
        self.offload = Offload()  # reading saved files and checking uploads, off this process
        # beside the scenes, below their priority: a scene's ticks never wait for them
        self.resimulations = Offload(("resimulations", limits.resimulations),  # minutes, maybe:
                                     "resimulations", BESIDE_NICE, per_call=True)  # each ends with its caller
        self.replays = Offload(("replayReads", limits.replay_reads), "replay reads",
                               BESIDE_NICE)  # JSON parsing: not in this process
        self.files = Offload(("fileJobs", limits.file_jobs), "robot files", BESIDE_NICE)
        self._setups: dict[str, SceneSetup] = {}
        self._restarts: dict[str, float] = {}  # a failed setup scene's next pause
        self.runners = runners  # scene processes here, or on a cluster's workers (server.cluster)
        self.checks: list[Callable[[], list[str]]] = []  # more problems: the cluster's bus
        self.ids = ids if ids is not None else ClientIds(state)
        self.recordings = Recordings(state.root / "recordings" if state is not None else None,
                                     limits)

    def get(self, name: str) -> SceneHub | None:
        """The hub of an existing scene."""
        return self.scenes.get(name)

    def prepare(self, name: str, setup: SceneSetup) -> None:
        """Let ``setup`` prepare the scene ``name`` whenever it starts."""
        self._setups[name] = setup

    def open(self, name: str) -> SceneHub:
        """The hub of a scene, made and started if it does not exist (or its process ended),
        prepared by its setup (:meth:`prepare`) each time it starts."""
        hub = self.scenes.get(name)
        if hub is not None and hub.ended:
            del self.scenes[name]
            hub = None
        if hub is None:
            if not SCENE_NAME.fullmatch(name):
                raise OutOfRange(f"scene names are 1-64 letters, digits, _ or -; got {name!r}"
                                 if len(name) <= 80 else "scene names are 1-64 letters, "
                                 "digits, _ or -")
            if len(self.scenes) >= self.limits.scenes:
                raise LimitExceeded(f"the server runs the maximum of {self.limits.scenes} scenes",
                                    limit="scenes", value=self.limits.scenes)
            store = self.state.store(name) if self.state is not None else None
            hub = self.scenes[name] = SceneHub(name, self.limits, self.tick_rate,
                                               self.assets, self._setups.get(name), store,
                                               self.reserve, self._ended, self.recordings,
                                               self.runners)
            hub.runner.start(after=self._stopping.pop(name, None))
        return hub

    def _ended(self, hub: SceneHub, failed: bool) -> None:
        """A scene's process ended: the server's own scenes start again by themselves (after
        a pause that grows while they keep failing); others when a client comes back. One
        refused (a cluster without room) never ran: it is forgotten, not reported failed."""
        self.recordings.scene_ended(hub.name)
        own = hub.name in self._setups or hub.name == DEFAULT_SCENE
        if hub.refusal is not None and not own and self.scenes.get(hub.name) is hub:
            del self.scenes[hub.name]
        if not failed or not own:
            return
        low, high = RESTART_SECONDS
        pause = self._restarts.get(hub.name, low)
        self._restarts[hub.name] = min(high, pause * 2)
        log.error("scene %s failed; it starts again in %.0f s", hub.name, pause)
        asyncio.get_running_loop().call_later(pause, self._restart, hub)

    def restart_failed(self) -> None:
        """Start the server's own failed scenes now, not after their growing pause (what
        failed them is back: a cluster's bus)."""
        for name, hub in list(self.scenes.items()):
            if hub.ended and hub.failed and (name in self._setups or name == DEFAULT_SCENE):
                self._restarts.pop(name, None)
                self._restart(hub)

    def _restart(self, hub: SceneHub) -> None:
        if self.scenes.get(hub.name) is hub:  # nobody opened it meanwhile
            try:
                self.open(hub.name)
            except VPError as error:
                log.error("scene %s could not start again: %s", hub.name, error.message)

    def client_for(self, scene: str, resume: str | None) -> tuple[str, str]:
        """The client id of a connection and its resume key: the id ``resume`` names when
        it is one this server gave for this scene (the client is back), else a new one."""
        if resume is not None:
            client_id, _, _ = resume.partition(":")
            if hmac.compare_digest(resume.encode(), self._resume_key(scene, client_id).encode()):
                return client_id, resume
        client_id = self.new_client_id()
        return client_id, self._resume_key(scene, client_id)

    def _resume_key(self, scene: str, client_id: str) -> str:
        mac = hmac.new(self.ids.secret, f"{scene}\0{client_id}".encode(), hashlib.sha256)
        return f"{client_id}:{mac.hexdigest()[:32]}"

    def new_client_id(self) -> str:
        """A fresh client id: c1, c2, … (never handed out twice by this server, nor, with
        a state folder, by the server before a restart)."""
        return f"c{self.ids.next()}"

    def reserve(self, owners: list[str]) -> None:
        """Never hand out these client ids (owners of objects a document brought in)."""
        numbers = [int(owner[1:]) for owner in owners if CLIENT_ID.fullmatch(owner)]
        if numbers:
            self.ids.reserve(max(numbers))

    def discard(self, hub: SceneHub) -> None:
        """Stop a scene nobody has joined (made for an import that was refused)."""
        if self.scenes.get(hub.name) is hub and not hub.members:
            hub.runner.stop()
            self._stopping[hub.name] = self.scenes.pop(hub.name).runner

    def problems(self) -> list[str]:
        """What fails now, in words (``/api/health``): scenes that failed or are silent,
        scenes whose changes cannot be saved, the state folder."""
        found = []
        for hub in list(self.scenes.values()):
            state = hub.state
            if state == "failed":
                found.append(f"scene {hub.name} failed (its process ended)" +
                             ("; it starts again by itself" if hub.name in self._setups
                              or hub.name == DEFAULT_SCENE else
                              "; it starts again when a client connects"))
            elif state == "unresponsive":
                found.append(f"scene {hub.name} has sent nothing for {hub.silent:.0f} s")
            if hub.saving.get("saveError"):
                found.append(f"scene {hub.name}: {hub.saving['saveError']}" +
                             ("; its changes last only until the server stops"
                              if hub.saving.get("durable") is False else
                              "; clients' changes are kept in its journal"))
        if self.state is not None:
            found += self.state.problems.values()
        for check in self.checks:
            found += check()
        return found

    async def remove_idle(self, now: float) -> list[str]:
        """Stop the scenes that have had no client for the grace period and hold nothing
        (or are saved: they come back as they were); their names."""
        grace = self.limits.scene_idle_seconds
        idle = [hub for name, hub in self.scenes.items() if name != DEFAULT_SCENE
                and not hub.members and hub.idle_since is not None
                and now - hub.idle_since >= grace]
        removed = []
        for hub in idle:
            if not hub.stored and await self._holds_objects(hub):
                continue  # kept objects: they stay while the server runs
            if self.scenes.get(hub.name) is hub and not hub.members:
                hub.runner.stop()
                self._stopping[hub.name] = self.scenes.pop(hub.name).runner
                self.removed += 1
                removed.append(hub.name)
        return removed

    @staticmethod
    async def _ask(hub: SceneHub, question: Callable[[Scene], Any]) -> Any | None:
        """``question(scene)``, answered in the scene's process; None once it has ended."""
        try:
            return json.loads(await hub.runner.call(Read(question)))
        except UnknownScene:
            return None

    async def _holds_objects(self, hub: SceneHub) -> bool:
        return (await self._ask(hub, clients_objects) or 0) > 0

    async def uploads_in_use(self) -> set[str]:
        """The uploaded files that running scenes and saved ones are made of."""
        names: set[str] = set()
        for hub in list(self.scenes.values()):
            # an ended scene's files are in its saved file, if it has one
            names.update(await self._ask(hub, uploaded_assets) or ())
        if self.state is not None:
            stopping = [r for r in self._stopping.values() if not r.ended]
            # their last saves first
            await asyncio.to_thread(lambda: [r.join(PREDECESSOR_SECONDS) for r in stopping])
            stores = [self.state.store(name) for name in self.state.saved_scenes()]
            names.update(await self.offload.run(_saved_asset_names, stores))
        return names

    async def sweep(self) -> None:
        """Remove idle scenes, forever (a task of the server's lifetime)."""
        while True:
            await asyncio.sleep(min(5.0, self.limits.scene_idle_seconds / 2))
            for name in await self.remove_idle(time.monotonic()):
                log.info("removed scene %s: no clients for %d s", name,
                         self.limits.scene_idle_seconds)
            self._stopping = {name: runner for name, runner in self._stopping.items()
                              if not runner.ended}
            heap.trim()  # what past floods of messages used goes back to the system

    async def stop(self) -> list[str]:
        """Stop every scene and wait for their processes to end; the scenes whose last
        changes could not be saved."""
        runners = [hub.runner for hub in self.scenes.values()]
        self.scenes.clear()
        for runner in runners:
            runner.stop()
        runners += self._stopping.values()  # removed a moment ago: their last saves
        self._stopping.clear()
        self.offload.close()
        self.resimulations.close()
        self.replays.close()
        self.files.close()
        await asyncio.to_thread(lambda: [runner.join(10) for runner in runners])
        self.recordings.close()  # after the processes finished their files
        return sorted({runner.name for runner in runners if runner.unsaved})
