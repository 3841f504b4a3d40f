"""A scene process's pipe as the event loop's own socket: lists of commands out, lists of
events in, each pickled and framed as :mod:`multiprocessing.connection` frames them (the
scene's process reads and writes its end with a ``Connection``).

The loop reads and writes the pipe itself, without a thread of its own for each way:
through threads, each message crossed to the loop with a wake-up of a blocked thread, a
hand-over of the interpreter's lock and a wake-up of the loop (22 % of the web process's
CPU while a script animated ten hands went to switching threads). What the scene's process
does not read at once waits in the transport's buffer, as it waited in a queue before.
"""

from __future__ import annotations

import asyncio
import pickle
import struct
from typing import Any, Callable

_LENGTH = struct.Struct("!i")  # multiprocessing's header: a length, or -1 then a long one
_LONG_LENGTH = struct.Struct("!Q")
_LONGEST_SHORT = 0x7FFFFFFF


def framed(value: Any) -> bytes:
    """``value`` pickled, as ``Connection.send`` writes it."""
    body = pickle.dumps(value, pickle.HIGHEST_PROTOCOL)
    if len(body) > _LONGEST_SHORT:
        return _LENGTH.pack(-1) + _LONG_LENGTH.pack(len(body)) + body
    return _LENGTH.pack(len(body)) + body


def _next(buffer: bytearray, start: int) -> tuple[int, int] | None:
    """Where the body of the message at ``start`` in ``buffer`` begins and ends (the next
    message's start); None until it has all come."""
    if len(buffer) - start < _LENGTH.size:
        return None
    (size,) = _LENGTH.unpack_from(buffer, start)
    first = start + _LENGTH.size
    if size == -1:
        if len(buffer) - first < _LONG_LENGTH.size:
            return None
        (size,) = _LONG_LENGTH.unpack_from(buffer, first)
        first += _LONG_LENGTH.size
    return (first, first + size) if len(buffer) >= first + size else None


class ProcessPipe(asyncio.Protocol):
    """The server's end of a scene's pipe: ``receive`` gets every value the scene's process
    sent, in order; ``lost`` is called once the pipe closes (the process ended)."""

    def __init__(self, receive: Callable[[Any], None], lost: Callable[[], None]) -> None:
        self._receive, self._lost = receive, lost
        self._buffer = bytearray()
        self.transport: asyncio.Transport | None = None

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        self.transport = transport  # type: ignore[assignment]

    def data_received(self, data: bytes) -> None:
        buffer = self._buffer
        buffer += data
        start, values = 0, []
        with memoryview(buffer) as view:
            while (found := _next(buffer, start)) is not None:
                first, start = found
                with view[first:start] as body:
                    values.append(pickle.loads(body))
        del buffer[:start]
        for value in values:
            self._receive(value)

    def send(self, value: Any) -> None:
        """Pickle and write ``value`` (buffered while the scene's process does not read)."""
        if self.transport is not None and not self.transport.is_closing():
            self.transport.write(framed(value))

    def connection_lost(self, exc: Exception | None) -> None:
        self._lost()
