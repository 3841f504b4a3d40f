"""WebSocket frames made once and written whole to every socket that is keeping up.

A server's frames are not masked (RFC 6455 §5.1), so one message is the same bytes on
every connection: a scene's frame is framed once (:func:`.outgoing.frame_of`, websockets' own
serializer) and those bytes are written straight to each viewer's transport. Through
ASGI, Starlette and uvicorn encode and frame the text again for every connection, in a
task woken per message: about 10 µs of the loop per viewer-frame, where the write itself
(one ``send`` on the socket) is about 3 (bench/fanout_floor.py).

uvicorn's WebSocket protocol has no way to write prepared bytes, and ASGI none to reach
the transport, so :class:`FramedSocketProtocol` is uvicorn's own sans-I/O protocol with
one more ASGI extension (``scope["extensions"][EXTENSION]``): the protocol itself, which
writes a whole frame only while the connection is open, its handshake done and no close
sent or received. It is not offered where compression may be negotiated (it would
change a frame's bytes per connection).
"""

from __future__ import annotations

import os
from asyncio import BaseTransport
from typing import Any, Protocol

from uvicorn.protocols.utils import ClientDisconnected, is_ssl
from uvicorn.protocols.websockets.websockets_sansio_impl import WebSocketsSansIOProtocol
from websockets.http11 import Request
from websockets.protocol import State

EXTENSION = "vp.framed"


class FramedSocket(Protocol):
    """What a connection's writer needs of its socket."""

    def write_now(self, frame: bytes) -> bool: ...

    async def write(self, frame: bytes) -> None: ...


def _state(name: str, initial: object) -> property:
    """One of uvicorn's own attributes of a connection's state, kept so that setting it
    (wherever uvicorn does) brings :attr:`FramedSocketProtocol.ready` up to date."""
    key = "_vp_" + name

    def get(self: FramedSocketProtocol) -> object:
        return self.__dict__.get(key, initial)

    def put(self: FramedSocketProtocol, value: object) -> None:
        self.__dict__[key] = value
        self._refresh()
    return property(get, put)


class FramedSocketProtocol(WebSocketsSansIOProtocol):
    """uvicorn's WebSocket protocol, able to write frames made once for many sockets.

    Whether a frame may be written at once is one flag, :attr:`ready`, brought up to date
    when the connection's state changes (uvicorn's own attributes, the websockets state
    after data arrives, the transport's high-water mark), not worked out again for every
    frame: for a thousand viewers of a scene that was a fifth of a viewer-frame's CPU.
    """

    handshake_complete = _state("handshake_complete", False)
    close_sent = _state("close_sent", False)
    disconnected = _state("disconnected", False)
    initial_response = _state("initial_response", None)
    ready = False  # a frame may be written now (open, handshake done, no close, below the mark)
    _paused = False  # the transport's buffer passed its high-water mark
    _fd: int | None = None  # the socket, written directly while the transport holds nothing

    def _refresh(self) -> None:
        conn = self.__dict__.get("conn")
        self.ready = (conn is not None and conn.state is State.OPEN and not self._paused
                      and self.handshake_complete and not self.close_sent
                      and not self.disconnected and self.initial_response is None)

    def handle_connect(self, event: Request) -> None:
        super().handle_connect(event)
        if not (self.close_sent or self.config.ws_per_message_deflate):  # the app will run
            self.scope["extensions"][EXTENSION] = {"socket": self}

    async def send(self, message: Any) -> None:
        await super().send(message)
        self._refresh()  # (accepted: uvicorn completes the handshake before the state opens)

    def data_received(self, data: bytes) -> None:
        super().data_received(data)
        self._refresh()  # (a close frame received: the state is no longer open)

    def pause_writing(self) -> None:
        super().pause_writing()
        self._paused = True
        self._refresh()

    def resume_writing(self) -> None:
        super().resume_writing()
        self._paused = False
        self._refresh()

    def shutdown(self) -> None:
        super().shutdown()
        self._refresh()

    def keepalive_timeout(self) -> None:
        """A ping unanswered for the timeout closes the connection (1011), unless the
        server itself is not reading it: the app holds a client's reading back while its
        scene has not applied what it sent (``server.web.http.socket``), and the pong then
        waits unread in the socket. Its answer is then awaited for another timeout; once
        reading resumes, a dead peer is found as before."""
        if self.read_paused and not self.transport.is_closing():
            self.pong_timer = self.loop.call_later(self.ping_timeout, self.keepalive_timeout)
            return
        super().keepalive_timeout()

    def connection_made(self, transport: BaseTransport) -> None:
        super().connection_made(transport)
        socket = transport.get_extra_info("socket")
        plain = socket is not None and not is_ssl(self.transport)  # (TLS: its transport writes)
        self._fd = socket.fileno() if plain else None

    def write_now(self, frame: bytes) -> bool:
        """Write ``frame`` at once if the socket is open and its buffer below the
        transport's high-water mark; False (nothing written) otherwise.

        While the transport holds nothing back, the frame goes to the socket in one write
        system call, as a bare fan-out loop would: asyncio's ``write`` takes a third more
        of a viewer-frame's CPU (8.7 us against 6.1 for the bare loop, a thousand viewers).
        What the socket does not take, or an error, the transport handles as it would have."""
        transport = self.transport
        if not self.ready or transport.is_closing():
            return False
        if self._fd is not None and not transport.get_write_buffer_size():
            try:
                sent = os.write(self._fd, frame)
            except OSError:  # full (the rest waits in the transport), or the peer is gone
                sent = 0
            if sent == len(frame):
                return True
            frame = frame[sent:]
        transport.write(frame)
        return True

    async def write(self, frame: bytes) -> None:
        """Write ``frame`` once the buffer is below the high-water mark; raises
        ``ClientDisconnected`` (an ``OSError``) if the connection is closing."""
        await self.writable.wait()  # (set again when the connection is lost)
        if not self.write_now(frame):
            raise ClientDisconnected()


def framed_socket(scope: dict[str, Any]) -> FramedSocket | None:
    """The connection's framed socket, when its server offers one (``vp-server`` does)."""
    found = scope.get("extensions", {}).get(EXTENSION)
    return found["socket"] if found else None
