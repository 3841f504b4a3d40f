"""Placing scenes on a real bus's workers: the least busy first, and scenes placed at the
same moment by two gateways spread over the workers instead of piling on one."""

from __future__ import annotations

import asyncio
from collections import Counter

from server.cluster.bus import Bus
from server.cluster.placement import Placement


def test_scenes_placed_at_once_by_two_gateways_spread_over_the_workers(workers_only, scene_name):
    async def place_at_once() -> Counter[str]:
        one, two = await Bus.connect(workers_only.url, "g1", 3.0), await Bus.connect(workers_only.url, "g2", 3.0)
        first, second = Placement(one), Placement(two)  # fresh: what a gateway just started knows
        placed = await asyncio.gather(*(
            (first if k % 2 else second).place(f"test-{k}", f"{scene_name}p{k}") for k in range(16)))
        await one.close()
        await two.close()
        return Counter(worker for worker, answer in placed)

    workers = asyncio.run(place_at_once())
    assert sum(workers.values()) == 16 and abs(workers["wa"] - workers["wb"]) <= 2
