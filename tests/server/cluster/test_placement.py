"""Placing scenes on a real bus's workers: the least busy first, and scenes placed at the
same moment by two gateways spread over the workers instead of piling on one."""

from __future__ import annotations

import asyncio
import os
import signal
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor

from websockets.sync.client import connect

from server.cluster.bus import Bus
from server.cluster.placement import Placement
from tests.server.web.ws_requests import next_message

from .conftest import Cluster, holder, running_bus


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


def test_a_scene_its_client_left_no_longer_sends_the_next_scenes_elsewhere(tmp_path):
    """Gymnasium's vector: a probe environment's scene is made and left, then the vector's
    two scenes are made at once; the worker that ran the probe's tells the gateway at once
    that it is free again, so they spread (with the load as of the probe's placement, the
    second went to either worker at random)."""
    with running_bus(tmp_path) as url:
        cluster = Cluster(url, tmp_path, gateways=1)
        try:
            ws = cluster.gateways[0].ws
            for round in range(2):  # (each round failed about one run in two before)
                with connect(f"{ws}/ws?scene=probe{round}") as probe:
                    next_message(probe, "snapshot")
                time.sleep(0.2)  # (its leave reaches the worker; the gateway surveys each second)
                scenes = [f"vector{round}a", f"vector{round}b"]
                with ThreadPoolExecutor(2) as pool:
                    clients = list(pool.map(lambda s: connect(f"{ws}/ws?scene={s}").__enter__(), scenes))
                for client in clients:
                    next_message(client, "snapshot")
                assert sorted(holder(url, scene) for scene in scenes) == ["wa", "wb"], round
                for client in clients:
                    client.close()
                time.sleep(0.3)
        finally:
            cluster.close()


def test_a_survey_hears_a_living_worker_that_is_slow_to_answer(tmp_path, scene_name):
    """A worker stopped for half a second (a loaded machine) when a fresh gateway places two
    scenes at once: the survey waits for every worker the bus knows to be alive, so they
    spread (a survey of a fixed 0.2 s put both on the worker that had answered)."""
    with running_bus(tmp_path) as url:
        cluster = Cluster(url, tmp_path, gateways=0)
        slow = cluster.workers["wb"].pid

        async def place_two() -> list[str]:
            bus = await Bus.connect(url, "g1", 3.0)
            placement = Placement(bus)
            os.kill(slow, signal.SIGSTOP)
            asyncio.get_running_loop().call_later(0.5, os.kill, slow, signal.SIGCONT)
            try:
                placed = await asyncio.gather(*(placement.place(f"test-{k}", f"{scene_name}s{k}")
                                                for k in range(2)))
            finally:
                os.kill(slow, signal.SIGCONT)
                await bus.close()
            return sorted(worker for worker, _ in placed)
        try:
            assert asyncio.run(place_two()) == ["wa", "wb"]
        finally:
            cluster.close()
