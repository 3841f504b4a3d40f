"""Light viewers: many WebSocket connections to one scene, noting when each frame arrives.

``python -m bench.viewers WS_URL SCENE COUNT SECONDS [--stalled]``: COUNT viewer
connections in one asyncio process; each notes its frames' arrival times and sequence
numbers (read from the message's head, not decoded: the readers must stay light). With
``--stalled`` one more connection does the WebSocket handshake and then never reads.
Prints, as JSON, per viewer: frames, frames per second, late frames (more than two tick
periods after the previous one) and frames skipped (sequence numbers never received).
"""

from __future__ import annotations

import asyncio
import json
import re
import socket
import sys
import time
from typing import Any
from urllib.parse import urlparse

from websockets.asyncio.client import connect

LATE_AFTER = 2 / 60  # seconds between two frames: one frame or more went missing
_SEQ = re.compile(r'"op":"frame","seq":(\d+)')


async def viewer(url: str, window: list[float], connected: asyncio.Semaphore) -> dict[str, Any]:
    """One viewer's frames within ``window`` (start and end, monotonic, set once every
    viewer is connected; frames before it are read and not counted)."""
    arrivals: list[float] = []
    seqs: list[int] = []
    async with connect(url, max_size=None, compression=None) as ws:
        connected.release()
        while not window or (left := window[1] - time.monotonic()) > 0:
            try:
                text = await asyncio.wait_for(ws.recv(), timeout=left if window else 1)
            except asyncio.TimeoutError:
                continue
            match = _SEQ.search(text, 0, 60)
            if match and window and time.monotonic() >= window[0]:
                arrivals.append(time.monotonic())
                seqs.append(int(match.group(1)))
    return summary(arrivals, seqs)


def summary(arrivals: list[float], seqs: list[int]) -> dict[str, Any]:
    """Frames, frames per second, late frames and skipped sequence numbers of one viewer."""
    span = arrivals[-1] - arrivals[0] if len(arrivals) > 1 else 0.0
    gaps = [b - a for a, b in zip(arrivals, arrivals[1:])]
    return {"frames": len(arrivals), "fps": (len(arrivals) - 1) / span if span else 0.0,
            "late": sum(1 for gap in gaps if gap > LATE_AFTER),
            "skipped": (seqs[-1] - seqs[0] + 1 - len(seqs)) if seqs else 0}


def stalled(url: str) -> socket.socket:
    """A connection that completes the WebSocket handshake and then never reads."""
    parts = urlparse(url)
    sock = socket.create_connection((parts.hostname, parts.port))
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    sock.sendall((f"GET {parts.path}?{parts.query} HTTP/1.1\r\nHost: {parts.netloc}\r\n"
                  "Upgrade: websocket\r\nConnection: Upgrade\r\n"
                  "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                  "Sec-WebSocket-Version: 13\r\n\r\n").encode())
    return sock


async def main(url: str, count: int, seconds: float, stall: bool) -> dict[str, Any]:
    stuck = stalled(url) if stall else None
    connected, window = asyncio.Semaphore(0), []
    tasks = [asyncio.create_task(viewer(url, window, connected)) for _ in range(count)]
    for _ in range(count):
        await asyncio.wait_for(connected.acquire(), timeout=60)
    start = time.monotonic() + 1  # past the snapshots and what queued while others connected
    window.extend([start, start + seconds])
    results = await asyncio.gather(*tasks)
    if stuck is not None:
        stuck.close()
    return {"viewers": results}


if __name__ == "__main__":
    base, scene, count, seconds = sys.argv[1:5]
    target = f"{base}/ws?scene={scene}&role=viewer"
    print(json.dumps(asyncio.run(main(target, int(count), float(seconds),
                                      "--stalled" in sys.argv))), flush=True)
