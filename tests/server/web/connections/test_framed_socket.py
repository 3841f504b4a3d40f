"""Frames made once and written whole: parsed by websockets itself, and written at once
only while the reader keeps up (a real uvicorn server with the protocol, a real client)."""

import asyncio
import contextlib
import json
import threading
import time

import pytest
import uvicorn
from websockets.frames import Frame, Opcode
from websockets.streams import StreamReader
from websockets.sync.client import connect

from server.web.connections.framed_socket import FramedSocketProtocol, framed_socket
from server.web.connections.outgoing import frame_of
from tests.conftest import WAIT_SECONDS, eventually, free_port


@pytest.mark.parametrize("text", ["{}", "é" * 100, "x" * 70_000])  # 7-, 16- and 64-bit lengths
def test_a_frame_made_once_is_one_text_message_to_a_client(text):
    reader = StreamReader()
    reader.feed_data(frame_of(text))
    parser = Frame.parse(reader.read_exact, mask=False)  # as a client reads a server's frame
    with pytest.raises(StopIteration) as parsed:
        next(parser)
    frame = parsed.value.value
    assert frame.opcode is Opcode.TEXT and frame.fin and frame.data.decode() == text


class Writer:
    """An ASGI app that writes ``count`` frames of ``size`` bytes as fast as it may,
    noting which could not be written at once."""

    def __init__(self, count: int, size: int) -> None:
        self.count, self.size = count, size
        self.waited: list[int] = []
        self.after_close: list[object] = []

    async def __call__(self, scope, receive, send) -> None:
        assert (await receive())["type"] == "websocket.connect"
        await send({"type": "websocket.accept"})
        socket = framed_socket(scope)
        for k in range(self.count):
            frame = frame_of(json.dumps({"k": k, "pad": "x" * self.size}))
            if not socket.write_now(frame):
                self.waited.append(k)
                await socket.write(frame)
        while (await receive())["type"] != "websocket.disconnect":
            pass
        await asyncio.sleep(0.05)  # the close handshake is over
        self.after_close.append(socket.write_now(frame_of("late")))
        try:
            await socket.write(frame_of("late"))
        except OSError as error:
            self.after_close.append(error)


@contextlib.contextmanager
def serving(app, deflate=False, ping_seconds=20.0, pong_seconds=None):
    """uvicorn serving ``app`` with the framed protocol, as vp-server does (a ping every
    ``ping_seconds``, its pong awaited ``pong_seconds``, by default as long); its ws URL."""
    server = uvicorn.Server(uvicorn.Config(app, port=free_port(), ws=FramedSocketProtocol,
                                           ws_per_message_deflate=deflate, lifespan="off",
                                           ws_ping_interval=ping_seconds,
                                           ws_ping_timeout=pong_seconds or ping_seconds,
                                           log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    try:
        eventually(lambda: server.started)
        yield f"ws://127.0.0.1:{server.config.port}/"
    finally:
        server.should_exit = True
        thread.join(WAIT_SECONDS)


def test_a_reader_that_lags_is_written_later_in_order_and_a_closed_one_not_at_all():
    writer = Writer(count=200, size=60_000)  # 12 MB: more than the sockets' buffers hold
    with serving(writer) as url:
        with connect(url, max_size=None, max_queue=4) as client:
            time.sleep(0.5)  # not reading: the client's queue, then both sockets fill
            ks = [json.loads(client.recv(timeout=WAIT_SECONDS))["k"] for _ in range(200)]
        assert ks == list(range(200))  # every frame, whole and in order
        assert writer.waited, "the writer never had to wait for the reader"
        assert writer.waited[0] > 0  # those before the buffers filled went at once
        eventually(lambda: len(writer.after_close) == 2)
        assert writer.after_close[0] is False and isinstance(writer.after_close[1], OSError)


def test_where_compression_may_be_negotiated_no_framed_socket_is_offered():
    offered = []

    async def app(scope, receive, send):
        await receive()
        offered.append(framed_socket(scope))
        await send({"type": "websocket.accept"})
        await send({"type": "websocket.send", "text": "compressed, per connection"})
        await receive()

    with serving(app, deflate=True) as url, connect(url) as client:
        assert client.recv(timeout=WAIT_SECONDS) == "compressed, per connection"
    assert offered == [None]


def test_a_client_whose_reading_the_server_holds_back_is_not_closed_for_a_pong_it_cannot_read():
    """The server stops reading a client whose text its scene has not applied yet (back
    pressure): its pongs wait unread meanwhile, and a keepalive that took that for a dead
    peer closed a driver with 1011 while a thousand viewers joined its scene."""
    got = []

    async def app(scope, receive, send):
        await receive()
        await send({"type": "websocket.accept"})
        got.append((await receive())["text"])
        await asyncio.sleep(5.0)  # held back past a ping's deadline: the client's pong unread
        while (message := await receive())["type"] != "websocket.disconnect":
            got.append(message["text"])
            await send({"type": "websocket.send", "text": f"read {len(got)}"})

    # a ping a second and 3 s for its pong (a pong of a loaded machine's test process, which
    # serves too, once came later than 1 s): the 5 s held back pass a ping's deadline
    with serving(app, ping_seconds=1.0, pong_seconds=3.0) as url, \
            connect(url, ping_interval=None) as client:
        for k in range(3):
            client.send(f"text {k}")
        assert client.recv(timeout=WAIT_SECONDS) == "read 2"  # not closed: 1011
        assert client.recv(timeout=WAIT_SECONDS) == "read 3"
        time.sleep(1.5)  # reading again: its pings are answered, nothing closes it
        client.send("text 3")
        assert client.recv(timeout=WAIT_SECONDS) == "read 4"
    assert got == [f"text {k}" for k in range(4)]
