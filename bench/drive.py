"""A client that builds a benchmark scene on a server and animates it at 60 Hz.

``python -m bench.drive WS_URL SCENE hands|arms COUNT SECONDS``: one batch message per
animation step (as the clients send a step's setters), incoming frames read and dropped
by a thread. Prints, as JSON, the steps sent and how many started late. Run as a process
of its own (lowered priority), as a client on another machine would be.
"""

from __future__ import annotations

import json
import sys
import threading
import time
from typing import Any, Callable

from websockets.exceptions import ConnectionClosed
from websockets.sync.client import ClientConnection, connect

from . import scenes

PERIOD = 1 / 60


def build(ws: ClientConnection, ops: list[dict[str, Any]]) -> None:
    """Send the scene's operations as one batch and wait for its answer (which must be ok)."""
    ws.send(json.dumps({"op": "batch", "id": 1, "ops": ops}))
    while True:
        message = json.loads(ws.recv(timeout=120))
        if message.get("id") == 1:
            assert message["op"] == "ok", message
            return


def drain(ws: ClientConnection) -> None:
    """Read and drop whatever arrives until the connection closes."""
    try:
        while True:
            ws.recv()
    except ConnectionClosed:
        pass


def animate(ws: ClientConnection, step: Callable[[int], list[dict[str, Any]]],
            seconds: float) -> dict[str, int]:
    """Send one step per period for ``seconds``; steps sent, and those more than half a
    period late (the driver itself fell behind)."""
    started = time.monotonic()
    sent = late = 0
    while (due := started + sent * PERIOD) < started + seconds:
        pause = due - time.monotonic()
        if pause > 0:
            time.sleep(pause)
        elif pause < -PERIOD / 2:
            late += 1
        ws.send(json.dumps({"op": "batch", "ops": step(sent)}))
        sent += 1
    return {"steps": sent, "late": late}


def main(url: str, scene: str, kind: str, count: int, seconds: float) -> dict[str, int]:
    # no pings of its own: the server's watch the connection, and a driver that gave up on
    # a swamped server (its pongs late) would leave the measure with no frames at all
    with connect(f"{url}/ws?scene={scene}", max_size=None, ping_interval=None) as ws:
        me = json.loads(ws.recv(timeout=30))["client"]
        if kind == "hands":
            build(ws, scenes.hands(me, count))
            step = lambda n: scenes.hand_step(me, count, n)  # noqa: E731
        else:
            build(ws, scenes.arms(me))
            step = lambda n: scenes.arm_step(me, n)  # noqa: E731
        threading.Thread(target=drain, args=(ws,), daemon=True).start()
        print(json.dumps({"ready": True}), flush=True)
        return animate(ws, step, seconds)


if __name__ == "__main__":
    url, scene, kind, count, seconds = sys.argv[1:6]
    print(json.dumps(main(url, scene, kind, int(count), float(seconds))), flush=True)
