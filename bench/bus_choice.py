"""NATS or Redis: the measurement the cluster's choice of bus rests on (issue 29).

Both servers from Debian, on loopback, each driven by its official Python client
(``nats-py``, ``redis``): 1 KiB frames published at 60 Hz to N subscribers (each its own
connection, as each gateway would be), and the round trip of a request answered by
another connection (a gateway asking a worker). Figures: delivery latency (median, p99),
frames lost, the broker's CPU per second, and the round trip's median and p99.

``python bench/bus_choice.py [--seconds S]``: prints JSON (written into RESULTS.md's notes
by hand; the choice is made once, not at every bench run).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import shutil
import socket
import subprocess
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Awaitable, Callable, Iterator

import nats
import redis.asyncio as aioredis

FRAME = 1024
RATE = 60.0
SUBSCRIBERS = (1, 10, 50, 200)
ROUND_TRIPS = 2000


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@contextmanager
def broker(kind: str) -> Iterator[tuple[str, int]]:
    """A NATS or Redis server on a free loopback port: its URL and pid."""
    port, folder = free_port(), Path(tempfile.mkdtemp(prefix=f"vp-{kind}-"))
    if kind == "nats":
        command = ["nats-server", "-a", "127.0.0.1", "-p", str(port), "-js", "-sd", str(folder)]
        url = f"nats://127.0.0.1:{port}"
    else:
        command = ["redis-server", "--port", str(port), "--bind", "127.0.0.1", "--save", "",
                   "--appendonly", "no", "--dir", str(folder)]
        url = f"redis://127.0.0.1:{port}"
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
                break
            except OSError:
                time.sleep(0.05)
        yield url, process.pid
    finally:
        process.terminate()
        process.wait(10)
        shutil.rmtree(folder, ignore_errors=True)


def cpu_seconds(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def summary(latencies: list[float], expected: int, cpu: float, seconds: float) -> dict[str, Any]:
    latencies.sort()
    pick = lambda q: round(latencies[min(len(latencies) - 1, int(q * len(latencies)))] * 1e3, 3)
    return {"median_ms": pick(0.5), "p99_ms": pick(0.99), "lost": expected - len(latencies),
            "broker_cpu_pct": round(100 * cpu / seconds, 1)}


async def publish_at_rate(publish: Callable[[bytes], Awaitable[Any]], seconds: float) -> int:
    """Frames of FRAME bytes (the send time first) at RATE a second; how many."""
    sent, start = 0, time.monotonic()
    while (now := time.monotonic()) - start < seconds:
        await publish(time.perf_counter_ns().to_bytes(8, "little") + bytes(FRAME - 8))
        sent += 1
        await asyncio.sleep(max(0.0, start + sent / RATE - time.monotonic()))
    return sent


def received(latencies: list[float]) -> Callable[[bytes], None]:
    def take(data: bytes) -> None:
        latencies.append((time.perf_counter_ns() - int.from_bytes(data[:8], "little")) / 1e9)
    return take


async def nats_fanout(url: str, pid: int, count: int, seconds: float) -> dict[str, Any]:
    latencies: list[float] = []
    take = received(latencies)
    subscribers = [await nats.connect(url) for _ in range(count)]
    for connection in subscribers:
        async def handler(message: Any) -> None:
            take(message.data)
        await connection.subscribe("scene.demo.frames", cb=handler)
        await connection.flush()
    publisher = await nats.connect(url)
    cpu = cpu_seconds(pid)
    sent = await publish_at_rate(lambda data: publisher.publish("scene.demo.frames", data), seconds)
    await asyncio.sleep(0.5)
    result = summary(latencies, sent * count, cpu_seconds(pid) - cpu, seconds)
    for connection in [*subscribers, publisher]:
        await connection.close()
    return result


async def redis_fanout(url: str, pid: int, count: int, seconds: float) -> dict[str, Any]:
    latencies: list[float] = []
    take = received(latencies)
    clients = [aioredis.from_url(url) for _ in range(count)]
    readers = []
    for client in clients:
        pubsub = client.pubsub()
        await pubsub.subscribe("scene.demo.frames")
        await pubsub.get_message(timeout=1)  # the subscription's confirmation

        async def read(pubsub: Any = pubsub) -> None:
            async for message in pubsub.listen():
                if message["type"] == "message":
                    take(message["data"])
        readers.append(asyncio.create_task(read()))
    publisher = aioredis.from_url(url)
    cpu = cpu_seconds(pid)
    sent = await publish_at_rate(lambda data: publisher.publish("scene.demo.frames", data), seconds)
    await asyncio.sleep(0.5)
    result = summary(latencies, sent * count, cpu_seconds(pid) - cpu, seconds)
    for task in readers:
        task.cancel()
    for client in [*clients, publisher]:
        await client.aclose()
    return result


async def nats_round_trip(url: str) -> dict[str, Any]:
    worker, gateway = await nats.connect(url), await nats.connect(url)

    async def answer(message: Any) -> None:
        await message.respond(message.data)
    await worker.subscribe("scene.demo.commands", cb=answer)
    await worker.flush()
    times = []
    for _ in range(ROUND_TRIPS):
        start = time.perf_counter()
        await gateway.request("scene.demo.commands", bytes(200), timeout=5)
        times.append(time.perf_counter() - start)
    await worker.close()
    await gateway.close()
    return summary(times, ROUND_TRIPS, 0.0, 1.0) | {"broker_cpu_pct": None}


async def redis_round_trip(url: str) -> dict[str, Any]:
    """Redis has no request/reply: a list the worker pops, a list per request for its answer."""
    worker, gateway = aioredis.from_url(url), aioredis.from_url(url)

    async def serve() -> None:
        while True:
            _, item = await worker.blpop(["scene.demo.commands"])
            reply_to, data = item.split(b"|", 1)
            await worker.rpush(reply_to, data)
    server = asyncio.create_task(serve())
    times = []
    for number in range(ROUND_TRIPS):
        start = time.perf_counter()
        reply_to = f"reply.{number}".encode()
        await gateway.rpush("scene.demo.commands", reply_to + b"|" + bytes(200))
        await gateway.blpop([reply_to], timeout=5)
        times.append(time.perf_counter() - start)
    server.cancel()
    await asyncio.gather(server, return_exceptions=True)
    await worker.aclose()
    await gateway.aclose()
    return summary(times, ROUND_TRIPS, 0.0, 1.0) | {"broker_cpu_pct": None}


async def measure(kind: str, seconds: float) -> dict[str, Any]:
    fanout = nats_fanout if kind == "nats" else redis_fanout
    round_trip = nats_round_trip if kind == "nats" else redis_round_trip
    with broker(kind) as (url, pid):
        figures = {f"frames_to_{n}": await fanout(url, pid, n, seconds) for n in SUBSCRIBERS}
        figures["round_trip"] = await round_trip(url)
    return figures


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seconds", type=float, default=5.0)
    args = parser.parse_args()
    print(json.dumps({kind: asyncio.run(measure(kind, args.seconds))
                      for kind in ("nats", "redis")}, indent=1))


if __name__ == "__main__":
    main()
