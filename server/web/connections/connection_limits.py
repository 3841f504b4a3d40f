"""Connection limits uvicorn does not have, and an event-loop log that does not flood.

:func:`guarded_protocol` makes uvicorn's h11 protocol class with: a deadline for the
request head (a connection that sends nothing, or a head slowly, is answered 408 and
closed), caps on open connections per server and per address (503), and a clear 431
for an upgrade request whose lines the WebSocket handshake could not read (uvicorn
would close it without an answer). :class:`LoopErrorLog` logs each kind of event-loop
error once a minute with a count (out of file descriptors, ``accept`` fails on every
attempt).
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections import Counter
from typing import Any

import h11
from uvicorn.protocols.http.h11_impl import H11Protocol

from ...core.kit.limits import Limits

log = logging.getLogger(__name__)
MAX_HANDSHAKE_LINE = 8000  # the WebSocket handshake reads lines of up to 8192 bytes


class ConnectionCount:
    """Open connections, in all and per address."""

    def __init__(self) -> None:
        self.total = 0
        self.by_address: Counter[str] = Counter()

    def open(self, address: str) -> None:
        self.total += 1
        self.by_address[address] += 1

    def close(self, address: str) -> None:
        self.total -= 1
        self.by_address[address] -= 1
        if not self.by_address[address]:
            del self.by_address[address]


def guarded_protocol(limits: Limits, count: ConnectionCount) -> type[H11Protocol]:
    """uvicorn's h11 protocol class with the server's connection limits."""

    class GuardedH11Protocol(H11Protocol):
        def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
            super().connection_made(transport)
            self._address = self.client[0] if self.client else "?"
            self._counted = True
            count.open(self._address)
            self._head_timer: asyncio.TimerHandle | None = None
            self._head = bytearray()  # the request head so far, until it is complete
            self._head_open = True
            if count.total > limits.connections:
                self._refuse(503, "the server has the maximum of connections open")
            elif count.by_address[self._address] > limits.connections_per_address:
                self._refuse(503, "this address has the maximum of connections open")
            else:
                self._head_timer = self.loop.call_later(limits.header_seconds, self._head_late)

        def connection_lost(self, exc: Exception | None) -> None:
            self._release()
            super().connection_lost(exc)

        def _release(self) -> None:
            if self._counted:
                self._counted = False
                count.close(self._address)
            if self._head_timer is not None:
                self._head_timer.cancel()
                self._head_timer = None

        def data_received(self, data: bytes) -> None:
            if self._head_open and not self._head_fits(data):
                self._refuse(431, f"request heads are limited to {limits.header_bytes} bytes")
                return
            super().data_received(data)
            if self._head_timer is not None and self.conn.their_state is not h11.IDLE:
                self._head_timer.cancel()
                self._head_timer = None

        def _head_fits(self, data: bytes) -> bool:
            self._head += data[:limits.header_bytes + 4]
            end = self._head.find(b"\r\n\r\n")
            if end >= 0:
                self._head_open, self._head = False, bytearray()
            return (end if end >= 0 else len(self._head)) <= limits.header_bytes

        def on_response_complete(self) -> None:
            super().on_response_complete()
            self._head_open, self._head = True, bytearray()  # the next request's head

        def _head_late(self) -> None:
            self._head_timer = None
            if self.conn.their_state is h11.IDLE and self.cycle is None:
                self._refuse(408, f"no request within {limits.header_seconds} s")

        def handle_websocket_upgrade(self, event: h11.Request) -> None:
            lines = [event.target] + [name + value for name, value in self.headers]
            if max(len(line) for line in lines) > MAX_HANDSHAKE_LINE:
                self._refuse(431, f"request lines are limited to {MAX_HANDSHAKE_LINE} bytes")
                return
            if self._head_timer is not None:
                self._head_timer.cancel()
                self._head_timer = None
            super().handle_websocket_upgrade(event)
            socket_protocol: Any = self.transport.get_protocol()
            lost = socket_protocol.connection_lost

            def release_then_lose(exc: Exception | None) -> None:
                self._release()
                lost(exc)
            socket_protocol.connection_lost = release_then_lose

        def _refuse(self, status: int, reason: str) -> None:
            body = reason.encode()
            head = (f"HTTP/1.1 {status} {h11_reason(status)}\r\ncontent-type: text/plain\r\n"
                    f"content-length: {len(body)}\r\nconnection: close\r\n\r\n").encode()
            if not self.transport.is_closing():
                self.transport.write(head + body)
                self.transport.close()

    return GuardedH11Protocol


def h11_reason(status: int) -> str:
    return {408: "Request Timeout", 431: "Request Header Fields Too Large",
            503: "Service Unavailable"}[status]


class LoopErrorLog:
    """An event-loop exception handler that logs each kind of error once a minute."""

    def __init__(self, every: float = 60.0) -> None:
        self._every = every
        self._last: dict[str, float] = {}
        self._repeats: Counter[str] = Counter()

    def handle(self, loop: asyncio.AbstractEventLoop, context: dict[str, Any]) -> None:
        kind = context.get("message", "event loop error")
        error = context.get("exception")
        if error is not None:
            kind = f"{kind}: {type(error).__name__}"
        now = time.monotonic()
        if now - self._last.get(kind, -self._every) < self._every:
            self._repeats[kind] += 1
            return
        repeats = self._repeats.pop(kind, 0)
        self._last[kind] = now
        suffix = f" (and {repeats} more like it since the last report)" if repeats else ""
        log.error("%s%s%s", kind, f": {error}" if error else "", suffix)
