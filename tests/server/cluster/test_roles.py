"""A process's part in the cluster: a worker answers placements on the bus under its name
until it stops; the bus's lease time is the first process's, and a later one that asked
for another is told so; names are made fit for bus subjects."""

from __future__ import annotations

import asyncio
import logging
import time

from server.cluster.bus import PLACE, Bus
from server.cluster.roles import ClusterMember, WorkerSettings, plain_name
from server.core.kit.limits import DEFAULT
from server.core.physics.assets import AssetLibrary
from tests.conftest import WAIT_SECONDS


def test_a_name_is_made_fit_for_a_bus_subject():
    assert plain_name("lab.example/worker 1") == "lab-example-worker-1"
    assert len(plain_name("x" * 100)) == 64


def worker(bus_url: str, name: str, lease_seconds: float) -> ClusterMember:
    settings = WorkerSettings(DEFAULT, 60.0, AssetLibrary(), {}, None, name=name, cores=2.0)
    return ClusterMember(bus_url, "worker", settings, lease_seconds)


async def answering(bus: Bus, wanted: list[str]) -> list[str]:
    """The workers answering placements, asked until they are ``wanted`` (a loaded machine
    answers late) or WAIT_SECONDS passed."""
    deadline = time.monotonic() + WAIT_SECONDS
    while True:
        found = sorted(load.worker for load in await bus.gather(PLACE, None, 0.2))
        if found == wanted or time.monotonic() > deadline:
            return found


def test_a_worker_answers_on_the_bus_until_it_stops(bus_url, caplog):
    async def run() -> tuple[list[str], list[str], list[str]]:
        asking = await Bus.connect(bus_url, "test", 3.0)  # the first: leases last 3 s
        try:
            first, second = worker(bus_url, "w-one", 3.0), worker(bus_url, "w-two", 10.0)
            await first.start(None)
            await second.start(None)
            running = await answering(asking, ["w-one", "w-two"])
            unsaved = await first.stop() + await second.stop()
            return running, await answering(asking, []), unsaved
        finally:
            await asking.close()
    with caplog.at_level(logging.WARNING, logger="server.cluster.roles"):
        running, left, unsaved = asyncio.run(run())
    assert running == ["w-one", "w-two"] and left == [] and unsaved == []
    warned = [r.getMessage() for r in caplog.records if r.name == "server.cluster.roles"]
    assert len(warned) == 1 and "last 3 s" in warned[0] and "--lease-seconds 10" in warned[0]
