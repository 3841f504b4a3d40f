"""Leases on a real NATS server: one worker per scene; a worker's scenes free once its key
lapses or it is seen to have left; one write a renewal, however many scenes."""

from __future__ import annotations

import asyncio

from server.cluster.bus import Bus
from server.cluster.leases import Leases, break_worker, lease_holder


async def _workers(url: str, seconds: float) -> tuple[Bus, Leases, Leases]:
    bus = await Bus.connect(url, "test", seconds)
    a, b = Leases(bus.workers, bus.scenes, "wa"), Leases(bus.workers, bus.scenes, "wb")
    await a.start()
    await b.start()
    return bus, a, b


def test_a_scene_is_held_by_one_worker_until_released(bus_url):
    async def run() -> list[object]:
        bus, a, b = await _workers(bus_url, 3.0)
        holder = lambda: lease_holder(bus.workers, bus.scenes, "lab")
        seen = [await a.claim("lab"), await b.claim("lab"), await holder()]
        await a.release("lab")
        seen += [await holder(), await b.claim("lab"), await holder(), "lab" in a]
        await bus.close()
        return seen
    assert asyncio.run(run()) == [None, "wa", "wa", None, None, "wb", False]


def test_a_worker_that_stops_renewing_loses_its_scenes_and_learns_it(bus_url):
    async def run() -> list[object]:
        bus, a, b = await _workers(bus_url, 1.0)  # keys last a second here
        await a.claim("lab")
        await a.claim("shop")
        for _ in range(3):  # renewed: held past the key's lifetime
            await asyncio.sleep(0.5)
            assert await a.renew() == [] and await b.renew() == []
        held = await b.claim("lab")
        await asyncio.sleep(1.5)  # a stalls: its key lapses, b (renewing) takes one scene
        await b.renew()
        taken = await b.claim("lab"), await lease_holder(bus.workers, bus.scenes, "lab")
        lost = await a.renew()  # a wakes: back, without the scene it lost
        still = await lease_holder(bus.workers, bus.scenes, "shop")
        await bus.close()
        return [held, *taken, lost, still]
    assert asyncio.run(run()) == ["wa", None, "wb", ["lab"], "wa"]


def test_a_worker_seen_to_leave_frees_its_scenes_at_once(bus_url):
    async def run() -> list[object]:
        bus, a, b = await _workers(bus_url, 60.0)  # no lapse within the test
        await a.claim("lab")
        before = await b.claim("lab")
        await break_worker(bus.workers, "wa")
        after = await b.claim("lab"), await lease_holder(bus.workers, bus.scenes, "lab")
        await bus.close()
        return [before, *after]
    assert asyncio.run(run()) == ["wa", None, "wb"]
