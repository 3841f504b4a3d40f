"""Client ids shared by gateways through a real NATS server: never handed out twice, one
secret for resume keys, documents' owners reserved everywhere."""

from __future__ import annotations

import asyncio

from server.cluster.bus import Bus
from server.cluster.client_ids import BLOCK, SharedClientIds


def test_two_gateways_share_the_secret_and_never_hand_out_the_same_id(bus_url):
    async def run() -> tuple[list[int], list[int], bool]:
        bus = await Bus.connect(bus_url, "test", 3.0)
        first, second = await SharedClientIds.open(bus.shared), await SharedClientIds.open(bus.shared)
        ones, twos = [], []
        for _ in range(BLOCK * 2):  # past a block each: the next ones taken on the way
            await first.available()  # (what a new connection waits for: at once, mostly)
            ones.append(first.next())
            await second.available()
            twos.append(second.next())
        same = first.secret == second.secret and len(first.secret) == 32
        await bus.close()
        return ones, twos, same
    ones, twos, same = asyncio.run(run())
    assert same
    assert len(set(ones)) == len(ones) == len(twos) == len(set(twos))
    assert not set(ones) & set(twos)


def test_owners_a_document_brings_are_never_handed_out_by_any_gateway(bus_url):
    async def run() -> tuple[int, int]:
        bus = await Bus.connect(bus_url, "test", 3.0)
        first = await SharedClientIds.open(bus.shared)
        first.reserve(50_000)
        await first.available()
        after = first.next()
        later = await SharedClientIds.open(bus.shared)
        await bus.close()
        return after, later.next()
    after, later = asyncio.run(run())
    assert after == 50_001 and later > 50_000
