"""Leases on a real NATS server: one worker per scene, lapsing when not renewed."""

from __future__ import annotations

import asyncio

from server.cluster.bus import Bus
from server.cluster.leases import Leases, lease_holder


def test_a_scene_is_held_by_one_worker_until_released(bus_url):
    async def run() -> list[object]:
        bus = await Bus.connect(bus_url, "test", 3.0)
        a, b = Leases(bus.leases, "wa"), Leases(bus.leases, "wb")
        seen = [await a.claim("lab"), await b.claim("lab"), await lease_holder(bus.leases, "lab")]
        await a.release("lab")
        seen += [await b.claim("lab"), await lease_holder(bus.leases, "lab"), "lab" in a]
        await bus.close()
        return seen
    assert asyncio.run(run()) == [None, "wa", "wa", None, "wb", False]


def test_a_lease_not_renewed_lapses_and_its_old_holder_learns_it_lost_it(bus_url):
    async def run() -> list[object]:
        bus = await Bus.connect(bus_url, "test", 1.0)  # leases last a second here
        a, b = Leases(bus.leases, "wa"), Leases(bus.leases, "wb")
        await a.claim("lab")
        await asyncio.sleep(0.5)
        assert await a.renew() == []  # renewed: still held after the first second
        await asyncio.sleep(0.7)
        held = await b.claim("lab")
        await asyncio.sleep(1.5)  # a, stalled, did not renew: b takes it
        taken = await b.claim("lab"), await lease_holder(bus.leases, "lab")
        await b.renew()
        lost = await a.renew()
        await bus.close()
        return [held, *taken, lost]
    assert asyncio.run(run()) == ["wa", None, "wb", ["lab"]]
