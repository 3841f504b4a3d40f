"""Placing scenes on a real bus's workers: the least busy first, and scenes placed at the
same moment by two gateways spread over the workers instead of piling on one."""

from __future__ import annotations

import asyncio
from collections import Counter

from server.cluster.bus import PLACE, Bus
from server.cluster.placement import Placement
from tests.conftest import eventually
from tests.server.cluster.conftest import ask_bus


def _loads(url: str, workers: frozenset[str] = frozenset({"wa", "wb"})) -> dict[str, int]:
    """The scenes each worker holds, once every one of ``workers`` has answered a survey (a
    worker busy starting scenes may miss a survey's 0.2 s)."""
    async def gather(bus: Bus) -> dict[str, int]:
        return {name: scenes for name, scenes, room in await bus.gather(PLACE, None, 0.2)}
    found: dict[str, int] = {}

    def answered() -> bool:
        found.clear()
        found.update(ask_bus(url, gather))
        return workers <= found.keys()
    eventually(answered)
    return found


def test_scenes_placed_at_once_by_two_gateways_spread_over_the_workers(workers_only, scene_name):
    before = _loads(workers_only.url)

    async def place_at_once() -> Counter[str]:
        one, two = await Bus.connect(workers_only.url, "g1", 3.0), await Bus.connect(workers_only.url, "g2", 3.0)
        first, second = Placement(one), Placement(two)  # fresh: what a gateway just started knows
        placed = await asyncio.gather(*(
            (first if k % 2 else second).place(f"test-{k}", f"{scene_name}p{k}") for k in range(16)))
        await one.close()
        await two.close()
        return Counter(worker for worker, answer in placed)

    workers = asyncio.run(place_at_once())
    assert sum(workers.values()) == 16 and set(workers) == {"wa", "wb"}
    after = _loads(workers_only.url)
    assert abs((after["wa"] - before["wa"]) - (after["wb"] - before["wb"])) <= 2
    assert abs(after["wa"] - after["wb"]) <= 2
