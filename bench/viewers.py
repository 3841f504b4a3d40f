"""Light viewers: many WebSocket connections to one scene, noting when each frame arrives.

``python -m bench.viewers WS_URL SCENE COUNT [--stalled]``: COUNT viewer connections in
one asyncio process; each notes its frames' arrival times and sequence numbers (read from
the message's head, not decoded) within a window its caller gives. With
``--stalled`` one more connection does the WebSocket handshake and then never reads.

It prints ``{"joined": n}`` once every viewer has had its first frame (n: how many have;
joining hundreds of viewers takes the server seconds) and reads its window from its input
(``{"window": [start, end]}``, monotonic clock, which the processes of one machine share:
viewer processes of one run count the same window, in which the caller measures the
servers' CPU; :func:`run_viewers` does this). Then it prints, as JSON, per viewer frames,
frames per second, late frames (more than two tick periods after the previous one) and
frames skipped (sequence numbers never received), and the CPU seconds it used.

The readers must stay light, or they, not the server, set what is measured on a shared
machine: each is an :class:`asyncio.Protocol` with no task or coroutine per message (the
library's asyncio client took 2.3 times the CPU for 400 viewers), and after websockets
makes its handshake request each splits the server's frames itself
(:class:`ServerFrames`): websockets' sans-I/O parser took about 10 µs a frame, so 1 000
viewers' reader needed most of a core and, on two cores shared with the server, made
frames late that the server had sent in time.
"""

from __future__ import annotations

import asyncio
import json
import re
import socket
import subprocess
import sys
import time
from pathlib import Path
from typing import Any, Callable, TypeVar

from websockets.client import ClientProtocol
from websockets.frames import Frame, Opcode
from websockets.uri import parse_uri

ROOT = Path(__file__).resolve().parents[1]
T = TypeVar("T")
LATE_AFTER = 2 / 60  # seconds between two frames: one frame or more went missing
FIRST_FRAME_SECONDS = 120.0  # for every viewer to have its first frame
_SEQ = re.compile(rb'"op":"frame","seq":(\d+)')


class ServerFrames:
    """The frames of a server's byte stream after its handshake: opcode and payload of
    each whole frame, in order.

    Written here, not taken from websockets, for speed alone (see the module's note): a
    server's frames are never masked (RFC 6455 §5.1) and this server sends no extensions,
    so a frame is a header of 2, 4 or 10 bytes and its payload; nothing is checked that a
    viewer's count does not need (tests/bench/test_viewers.py reads websockets' own frames)."""

    def __init__(self) -> None:
        self._buffer = bytearray()

    def feed(self, data: bytes) -> list[tuple[int, bytes]]:
        """The frames completed by ``data``: (opcode, payload) each."""
        buffer = self._buffer
        buffer += data
        frames, at, size = [], 0, len(buffer)
        while size - at >= 2:
            length, start = buffer[at + 1] & 0x7F, at + 2
            if length >= 126:
                start += 2 if length == 126 else 8
                if size < start:
                    break
                length = int.from_bytes(buffer[at + 2:start], "big")
            if size < start + length:
                break
            frames.append((buffer[at] & 0x0F, bytes(buffer[start:start + length])))
            at = start + length
        del buffer[:at]
        return frames


class Viewer(asyncio.Protocol):
    """One viewer connection: its frames' arrivals within ``window`` (start and end,
    monotonic, set once every viewer has had a frame)."""

    def __init__(self, url: str, window: list[float]) -> None:
        self.handshake = ClientProtocol(parse_uri(url), max_size=None)
        self.frames: ServerFrames | None = None  # once the server has switched protocols
        self._head = b""  # of its answer to the handshake, until it is whole
        self.window = window
        self.first_frame = asyncio.get_running_loop().create_future()
        self.arrivals: list[float] = []
        self.seqs: list[int] = []
        self.transport: asyncio.Transport | None = None

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        assert isinstance(transport, asyncio.Transport)
        self.transport = transport
        transport.write(self.handshake.connect().serialize())

    def data_received(self, data: bytes) -> None:
        if self.frames is None:
            data = self._switched(data)
        for opcode, payload in self.frames.feed(data) if self.frames is not None else ():
            if opcode == Opcode.PING.value:  # answered, or the server's keepalive ends us
                assert self.transport is not None
                self.transport.write(Frame(Opcode.PONG, payload).serialize(mask=True))
            elif opcode == Opcode.TEXT.value:
                self._arrived(payload)

    def _switched(self, data: bytes) -> bytes:
        """The bytes after the server's answer to the handshake, once it is whole."""
        head, end, rest = (self._head + data).partition(b"\r\n\r\n")
        if not end:
            self._head = head
            return b""
        if not head.startswith(b"HTTP/1.1 101"):
            raise ConnectionError(f"the handshake was refused: {head[:200]!r}")
        self.frames = ServerFrames()
        return rest

    def _arrived(self, payload: bytes) -> None:
        match = _SEQ.search(payload, 0, 60)
        if match is None:
            return
        if not self.first_frame.done():
            self.first_frame.set_result(True)
        now, window = time.monotonic(), self.window
        if window and window[0] <= now <= window[1]:
            self.arrivals.append(now)
            self.seqs.append(int(match.group(1)))

    def connection_lost(self, exc: Exception | None) -> None:
        if not self.first_frame.done():  # none will come: it counts with no frames
            self.first_frame.set_result(False)

    def summary(self) -> dict[str, Any]:
        return summary(self.arrivals, self.seqs)


def summary(arrivals: list[float], seqs: list[int]) -> dict[str, Any]:
    """Frames, frames per second, late frames and skipped sequence numbers of one viewer."""
    span = arrivals[-1] - arrivals[0] if len(arrivals) > 1 else 0.0
    gaps = [b - a for a, b in zip(arrivals, arrivals[1:])]
    return {"frames": len(arrivals), "fps": (len(arrivals) - 1) / span if span else 0.0,
            "late": sum(1 for gap in gaps if gap > LATE_AFTER),
            "skipped": (seqs[-1] - seqs[0] + 1 - len(seqs)) if seqs else 0}


def stalled(url: str) -> socket.socket:
    """A connection that completes the WebSocket handshake and then never reads."""
    uri = parse_uri(url)
    sock = socket.create_connection((uri.host, uri.port))
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    sock.sendall(ClientProtocol(uri).connect().serialize())
    return sock


async def main(url: str, count: int, stall: bool) -> dict[str, Any]:
    stuck = stalled(url) if stall else None
    loop, uri, window = asyncio.get_running_loop(), parse_uri(url), []
    viewers = [Viewer(url, window) for _ in range(count)]
    for viewer in viewers:  # one after another: a burst of handshakes is not what is measured
        await loop.create_connection(lambda v=viewer: v, uri.host, uri.port)
    # a viewer with no frame by then counts with none (its row fails), not the whole run
    await asyncio.wait([v.first_frame for v in viewers], timeout=FIRST_FRAME_SECONDS)
    joined = sum(1 for v in viewers if v.first_frame.done() and v.first_frame.result())
    print(json.dumps({"joined": joined}), flush=True)
    window.extend(json.loads(await asyncio.to_thread(sys.stdin.readline))["window"])
    await asyncio.sleep(window[1] - time.monotonic() + 0.05)
    for viewer in viewers:
        if viewer.transport is not None:
            viewer.transport.close()
    if stuck is not None:
        stuck.close()
    return {"viewers": [viewer.summary() for viewer in viewers],
            "cpu_seconds": time.process_time()}


def run_viewers(commands: list[list[str]], seconds: float,
                during: Callable[[float, float], T]) -> tuple[list[dict[str, Any]], T]:
    """Run viewer processes (``commands``: each ``python -m bench.viewers …``) over one
    window of ``seconds``, opened a second after every process has joined; what each
    printed at the end, and what ``during(start, end)`` returned (called once all have
    joined: it measures the servers within the window)."""
    processes = [subprocess.Popen(command, cwd=ROOT, stdin=subprocess.PIPE,
                                  stdout=subprocess.PIPE, text=True) for command in commands]
    for process in processes:
        assert process.stdout is not None
        json.loads(process.stdout.readline())  # {"joined": n}
    start = time.monotonic() + 1  # past the snapshots and what queued while others joined
    for process in processes:
        assert process.stdin is not None
        process.stdin.write(json.dumps({"window": [start, start + seconds]}) + "\n")
        process.stdin.flush()
    measured = during(start, start + seconds)
    outputs = []
    for process in processes:
        assert process.stdout is not None
        outputs.append(json.loads(process.stdout.read()))
        process.wait(60)
    return outputs, measured


def sleep_until(moment: float) -> None:
    time.sleep(max(0.0, moment - time.monotonic()))


if __name__ == "__main__":
    base, scene, count = sys.argv[1:4]
    target = f"{base}/ws?scene={scene}&role=viewer"
    print(json.dumps(asyncio.run(main(target, int(count), "--stalled" in sys.argv))), flush=True)
