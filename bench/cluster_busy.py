"""Busy scenes for :func:`bench.cluster.busy_scenes`: one client connection per scene
(``busy0`` … spread over the gateways), each building an edged hand and flexing its
fingers 10 times a second; frames are read and dropped.

``python -m bench.cluster_busy WS_URL [WS_URL …] COUNT SECONDS``: prints ``{"placed": n}``
and how many failed once every scene is built (or failed), then ``{"steps": n, "failed":
n}`` at the end.
"""

from __future__ import annotations

import asyncio
import json
import math
import sys
import time

from websockets.asyncio.client import ClientConnection, connect

RATE = 10.0


async def scene(url: str, name: str, built: asyncio.Event, go: asyncio.Event,
                seconds: float, counts: list[int]) -> None:
    try:
        await _scene(url, name, built, go, seconds, counts)
    except Exception as error:  # refused, or closed: counted, the others go on
        counts[3] += 1
        print(json.dumps({"scene": name, "error": str(error)[:200]}), file=sys.stderr)
        if counts[0] + counts[3] == counts[1]:
            built.set()


async def _scene(url: str, name: str, built: asyncio.Event, go: asyncio.Event,
                 seconds: float, counts: list[int]) -> None:
    async with connect(f"{url}/ws?scene={name}", max_size=None, compression=None,
                       open_timeout=120) as ws:
        hello = json.loads(await ws.recv())
        if hello.get("op") != "hello":
            raise RuntimeError(f"refused: {hello}")
        me = hello["client"]
        hand = f"{me}.hand"
        await ws.send(json.dumps({"op": "create", "id": 1, "object": hand, "type": "EdgedHand",
                                  "args": [True]}))
        while json.loads(await ws.recv()).get("id") != 1:
            pass
        counts[0] += 1
        if counts[0] + counts[3] == counts[1]:
            built.set()
        reader = asyncio.create_task(_drain(ws))
        await go.wait()
        started = time.monotonic()
        step = 0
        while (due := started + step / RATE) < started + seconds:
            await asyncio.sleep(max(0.0, due - time.monotonic()))
            await ws.send(json.dumps({"op": "call", "object": hand, "method": "flexFingers",
                                      "args": [0.5 + 0.5 * math.sin(step / 5)]}))
            step += 1
        counts[2] += step
        reader.cancel()


async def _drain(ws: ClientConnection) -> None:
    async for _ in ws:
        pass


async def main(urls: list[str], count: int, seconds: float) -> None:
    built, go = asyncio.Event(), asyncio.Event()
    counts = [0, count, 0, 0]  # built, wanted, steps sent, failed
    tasks = [asyncio.create_task(scene(urls[k % len(urls)], f"busy{k}", built, go, seconds,
                                       counts)) for k in range(count)]
    await asyncio.wait_for(built.wait(), timeout=600)
    print(json.dumps({"placed": counts[0], "failed": counts[3]}), flush=True)
    go.set()
    await asyncio.gather(*tasks)
    print(json.dumps({"steps": counts[2], "failed": counts[3]}), flush=True)


if __name__ == "__main__":
    *addresses, number, span = sys.argv[1:]
    asyncio.run(main(addresses, int(number), float(span)))
