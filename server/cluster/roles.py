"""What one ``vp-server --bus URL`` process is in the cluster: a gateway, a worker, or both
(``--role gateway|worker|all``), on one bus connection."""

from __future__ import annotations

import asyncio
import logging
import os
import re
import secrets
import signal
import socket
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping

from ..core.kit.limits import Limits
from ..core.physics.assets import AssetLibrary
from ..web.scenes.hub import Hubs
from ..web.storage.state_dir import StateDir
from ..web.process.scene_start import SceneSetup
from .bus import Bus
from .client_ids import SharedClientIds
from .gateway import Gateway
from .worker_host import WorkerHost

log = logging.getLogger(__name__)
ROLES = ("all", "gateway", "worker")
# a worker's scenes start elsewhere this long after it stopped answering, at most (at once
# when it left the bus: it died); long enough that a swamped machine's stalls are no death
LEASE_SECONDS = 10.0


def plain_name(text: str) -> str:
    """A name usable in bus subjects (letters, digits, ``_`` and ``-``)."""
    return re.sub(r"[^A-Za-z0-9_-]", "-", text)[:64]


def default_worker_name() -> str:
    return plain_name(f"{socket.gethostname()}-{os.getpid()}")


@dataclass
class WorkerSettings:
    """How a worker makes scenes: the same flags a single server takes."""

    limits: Limits
    tick_rate: float
    assets: AssetLibrary
    setups: Mapping[str, SceneSetup]
    state_dir: Path | None
    name: str = field(default_factory=default_worker_name)
    cores: float = field(default_factory=lambda: float(os.cpu_count() or 1))


class ClusterMember:
    """This process's part in the cluster; :func:`server.web.http.app.create_app` starts and
    stops it around its own life (a worker alone: :meth:`serve`)."""

    def __init__(self, url: str, role: str, worker: WorkerSettings,
                 lease_seconds: float = LEASE_SECONDS) -> None:
        self.url, self.role, self.settings = url, role, worker
        self.lease_seconds = lease_seconds
        self.bus: Bus | None = None
        self.gateway: Gateway | None = None
        self.host: WorkerHost | None = None

    async def start(self, hubs: Hubs | None) -> None:
        """Connect to the bus; serve ``hubs``' scenes through workers (a gateway), run
        scenes (a worker), or both."""
        name = f"g{secrets.token_hex(4)}" if self.role == "gateway" else self.settings.name
        self.bus = await Bus.connect(self.url, name, self.lease_seconds)
        if self.role in ("all", "worker"):
            if abs(self.bus.lease_seconds - self.lease_seconds) > 1e-6:
                log.warning("the bus's leases last %g s, as the first process to use it said; "
                            "--lease-seconds %g is not used", self.bus.lease_seconds,
                            self.lease_seconds)
            settings = self.settings
            state = StateDir(settings.state_dir) if settings.state_dir is not None else None
            self.host = WorkerHost(self.bus, settings.name, settings.limits, settings.tick_rate,
                                   settings.assets, settings.setups, state, settings.cores)
            await self.host.start()
        if hubs is not None and self.role in ("all", "gateway"):
            self.gateway = Gateway(self.bus, name if self.role == "gateway" else f"g-{name}")
            hubs.runners = self.gateway.runner
            hubs.checks.append(self.bus.link.problems)
            self.bus.link.returned.append(hubs.restart_failed)
            hubs.ids = await SharedClientIds.open(self.bus.shared)
            await self.gateway.start()
            log.info("gateway %s serves scenes through %s", self.gateway.name, self.url)

    async def stop(self) -> list[str]:
        """Leave the cluster: scenes run here stop (saved first); those that could not be."""
        unsaved: list[str] = []
        if self.gateway is not None:
            await self.gateway.stop()
        if self.host is not None:
            unsaved = await self.host.stop()
        if self.bus is not None:
            await self.bus.close()
        return unsaved

    async def serve(self) -> list[str]:
        """A worker alone: run scenes until SIGINT or SIGTERM."""
        stopped = asyncio.Event()
        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.add_signal_handler(sig, stopped.set)
        await self.start(None)
        await stopped.wait()
        return await self.stop()
