"""Connection limits on a real server: idle and slow connections, caps, long lines."""

import json
import socket
import time
import urllib.error

import pytest
from websockets.sync.client import connect

from tests.conftest import WAIT_SECONDS, eventually, start_server, stop_server


@pytest.fixture(scope="module")
def strict():
    """A server with small connection limits, so that tests reach them quickly."""
    running = start_server("--no-demo", "--limit", "headerSeconds=1",
                           "--limit", "connectionsPerAddress=8", "--limit", "sceneIdleSeconds=1",
                           "--ping-seconds", "1")
    yield running
    stop_server(running)


def raw(server, data=b""):
    conn = socket.create_connection(("127.0.0.1", server.port), timeout=WAIT_SECONDS)
    if data:
        conn.sendall(data)
    return conn


def read_all(conn):
    chunks = []
    while chunk := conn.recv(65536):
        chunks.append(chunk)
    return b"".join(chunks)


def answers_health(server) -> bool:
    """Whether the server answers this address again (503 while its connections are capped)."""
    try:
        return server.get("/api/health")["status"] == "ok"
    except urllib.error.HTTPError as refused:
        assert refused.code == 503
        return False


def test_a_connection_that_sends_nothing_is_closed_with_408(strict):
    with raw(strict) as idle, raw(strict, b"GET /api/health HTTP/1.1\r\nHost: x\r\n") as slow:
        started = time.monotonic()
        assert read_all(idle).startswith(b"HTTP/1.1 408")
        assert read_all(slow).startswith(b"HTTP/1.1 408")
        assert 1 <= time.monotonic() - started < WAIT_SECONDS  # after headerSeconds
    assert strict.get("/api/health")["status"] == "ok"


def test_connections_per_address_are_capped_and_freed(strict):
    held = [raw(strict) for _ in range(8)]
    try:
        with raw(strict) as extra:
            assert read_all(extra).startswith(b"HTTP/1.1 503")
    finally:
        for conn in held:
            conn.close()
    eventually(lambda: answers_health(strict))


def test_an_upgrade_line_too_long_for_the_handshake_gets_431(strict):
    target = "/ws?scene=a&pad=" + "x" * 9000
    head = (f"GET {target} HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
            f"Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n")
    with raw(strict, head.encode()) as conn:
        assert read_all(conn).startswith(b"HTTP/1.1 431")
    oversized = b"GET /api/health HTTP/1.1\r\nHost: x\r\nX-Pad: " + b"x" * 20_000 + b"\r\n\r\n"
    with raw(strict, oversized) as conn:
        assert read_all(conn).startswith(b"HTTP/1.1 4")


def test_a_silent_websocket_peer_is_closed_by_ping_timeout(strict):
    head = ("GET /ws?scene=silent HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\n"
            "Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
            "Sec-WebSocket-Version: 13\r\n\r\n")
    with raw(strict, head.encode()) as conn:  # completes the handshake, never answers a ping
        started = time.monotonic()
        received = read_all(conn)  # frames and pings arrive, then the server closes
        assert received.startswith(b"HTTP/1.1 101")
        assert b"\x89" in received  # a ping frame (opcode 9, final), never answered
        assert 1 <= time.monotonic() - started < WAIT_SECONDS  # after a ping unanswered
    eventually(lambda: {s["name"]: s["clients"] for s in strict.get("/api/scenes")}
               .get("silent", 0) == 0)


def test_scenes_without_clients_are_removed_after_the_grace_period(strict):
    with connect(f"{strict.ws}/ws?scene=passing") as ws:
        json.loads(ws.recv(timeout=WAIT_SECONDS))
    assert "passing" in [s["name"] for s in strict.get("/api/scenes")]
    deadline = time.monotonic() + WAIT_SECONDS
    while "passing" in [s["name"] for s in strict.get("/api/scenes")]:
        assert time.monotonic() < deadline
        time.sleep(0.2)
    assert "default" in [s["name"] for s in strict.get("/api/scenes")]
    with pytest.raises(urllib.error.HTTPError) as gone:
        strict.get("/api/scenes/passing/robots")
    assert gone.value.code == 404
    assert strict.get("/api/metrics")["scenesRemoved"] >= 1
