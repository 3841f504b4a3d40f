"""Busy scenes for :func:`bench.cluster.busy_scenes`: one client connection per scene
(``busy0`` … spread over the gateways), each building an edged hand and flexing its
fingers 10 times a second from then on; frames are read and dropped.

A scene refused because the cluster is full (``limit_exceeded``, closed with 1013 "try
again later") is asked for again every few seconds, as a client should, until
``PLACING_SECONDS`` have passed: the workers measure their new scenes' CPU once a second
and take more as long as what they measure leaves room.

``python -m bench.cluster_busy WS_URL [WS_URL …] COUNT SECONDS``: prints ``{"placed": n,
"failed": n}`` once every scene is built or given up, then ``{"steps": n, "failed": n}``
SECONDS later, at the end.
"""

from __future__ import annotations

import asyncio
import json
import math
import sys
import time
from dataclasses import dataclass, field

from websockets.asyncio.client import ClientConnection, connect

RATE = 10.0
PLACING_SECONDS = 60.0  # to be placed, after which a refused scene is given up
RETRY_SECONDS = 3.0


class Refused(Exception):
    """The cluster has no room: try again later."""


@dataclass
class Counts:
    wanted: int
    placed: int = 0
    failed: int = 0
    steps: int = 0
    settled: asyncio.Event = field(default_factory=asyncio.Event)  # every scene placed or failed
    stop: asyncio.Event = field(default_factory=asyncio.Event)

    def one_settled(self) -> None:
        if self.placed + self.failed == self.wanted:
            self.settled.set()


async def scene(url: str, name: str, counts: Counts) -> None:
    deadline = time.monotonic() + PLACING_SECONDS
    while True:
        try:
            return await _scene(url, name, counts)
        except Refused as refusal:
            if time.monotonic() + RETRY_SECONDS < deadline:
                await asyncio.sleep(RETRY_SECONDS)
                continue
            error: Exception = refusal
        except Exception as other:  # closed: counted, the others go on
            error = other
        counts.failed += 1
        print(json.dumps({"scene": name, "error": str(error)[:200]}), file=sys.stderr)
        counts.one_settled()
        return


async def _scene(url: str, name: str, counts: Counts) -> None:
    async with connect(f"{url}/ws?scene={name}", max_size=None, compression=None,
                       open_timeout=120) as ws:
        hello = json.loads(await ws.recv())
        if hello.get("code") == "limit_exceeded":
            raise Refused(hello["message"])
        if hello.get("op") != "hello":
            raise RuntimeError(f"refused: {hello}")
        hand = f"{hello['client']}.hand"
        await ws.send(json.dumps({"op": "create", "id": 1, "object": hand, "type": "EdgedHand",
                                  "args": [True]}))
        while json.loads(await ws.recv()).get("id") != 1:
            pass
        counts.placed += 1
        counts.one_settled()
        reader = asyncio.create_task(_drain(ws))
        started, step = time.monotonic(), 0
        while not counts.stop.is_set():
            await asyncio.sleep(max(0.0, started + step / RATE - time.monotonic()))
            await ws.send(json.dumps({"op": "call", "object": hand, "method": "flexFingers",
                                      "args": [0.5 + 0.5 * math.sin(step / 5)]}))
            step += 1
        counts.steps += step
        reader.cancel()


async def _drain(ws: ClientConnection) -> None:
    async for _ in ws:
        pass


async def main(urls: list[str], count: int, seconds: float) -> None:
    counts = Counts(count)
    tasks = [asyncio.create_task(scene(urls[k % len(urls)], f"busy{k}", counts))
             for k in range(count)]
    await asyncio.wait_for(counts.settled.wait(), timeout=PLACING_SECONDS + 300)
    print(json.dumps({"placed": counts.placed, "failed": counts.failed}), flush=True)
    await asyncio.sleep(seconds)
    counts.stop.set()
    await asyncio.gather(*tasks)
    print(json.dumps({"steps": counts.steps, "failed": counts.failed}), flush=True)


if __name__ == "__main__":
    *addresses, number, span = sys.argv[1:]
    asyncio.run(main(addresses, int(number), float(span)))
