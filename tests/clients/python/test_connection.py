"""A script whose connection drops comes back as the same client, with its robots,
nothing made twice (the network cut by a real TCP proxy between it and the server)."""

from __future__ import annotations

import socket
import struct
import threading
import time

import pytest

import virtual_prosthetics as vp
from tests.conftest import WAIT_SECONDS, start_server, stop_server


class CuttableProxy:
    """Forwards TCP from a local port to the server; :meth:`cut` drops every connection
    (as a lost network does) and keeps listening."""

    def __init__(self, target_port: int) -> None:
        self.target = target_port
        self.listener = socket.create_server(("127.0.0.1", 0))
        self.port = self.listener.getsockname()[1]
        self.open: list[socket.socket] = []
        self.accepted = 0
        self.reset_next = 0  # connections to drop at once (a server restarting)
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self) -> None:
        while True:
            try:
                client, _ = self.listener.accept()
            except OSError:
                return
            if self.reset_next:
                self.reset_next -= 1
                client.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
                client.close()  # a reset as the handshake begins
                continue
            upstream = socket.create_connection(("127.0.0.1", self.target))
            self.open += [client, upstream]
            self.accepted += 1
            for a, b in ((client, upstream), (upstream, client)):
                threading.Thread(target=self._pump, args=(a, b), daemon=True).start()

    @staticmethod
    def _pump(source: socket.socket, sink: socket.socket) -> None:
        try:
            while data := source.recv(65536):
                sink.sendall(data)
        except OSError:
            pass
        for end in (source, sink):
            try:
                end.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass

    def cut(self) -> None:
        ends, self.open = self.open, []  # not the connections made again meanwhile
        for end in ends:
            try:
                end.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass

    def close(self) -> None:
        self.cut()
        self.listener.close()


@pytest.fixture(scope="module")
def patient():
    """A server that keeps a left client's objects a minute: a client tries to connect
    again only as long as its objects are kept, and the shared server's second (as its
    tests want) was too short, on a loaded machine, for three dropped handshakes."""
    running = start_server("--no-demo", "--limit", f"leaveGraceSeconds={int(WAIT_SECONDS)}")
    yield running
    stop_server(running)


@pytest.fixture
def proxy(patient):
    running = CuttableProxy(patient.port)
    yield running
    running.close()


def test_a_dropped_script_comes_back_with_its_robots_and_makes_nothing_twice(patient, proxy,
                                                                            scene_name):
    with vp.connect(f"ws://127.0.0.1:{proxy.port}", scene=scene_name) as scene:
        me = scene.client_id
        hand = vp.EdgedHand()
        hand.flex_fingers(0.3)
        scene.sync()
        proxy.cut()
        deadline = time.monotonic() + WAIT_SECONDS
        while proxy.accepted < 2:  # requests sent into the dead link before the client
            assert time.monotonic() < deadline  # noticed would be reported lost
            time.sleep(0.01)
        hand.flex_fingers(0.6)  # sent once the client is itself again
        scene.sync()
        assert proxy.accepted == 2 and scene.client_id == me
        robots = patient.get(f"/api/scenes/{scene_name}/robots")
        assert [r["id"] for r in robots] == [hand.id]
        motors = patient.get(f"/api/scenes/{scene_name}/robots/{hand.id}")["motors"]
        assert motors[1]["angle"] == pytest.approx(-0.6)
        assert hand.get_angles()[1] == pytest.approx(-0.6)  # the mirror resynced and follows


def test_connections_dropped_mid_handshake_do_not_stop_the_reconnection(patient, proxy,
                                                                        scene_name):
    with vp.connect(f"ws://127.0.0.1:{proxy.port}", scene=scene_name) as scene:
        me = scene.client_id
        box = vp.Box()
        scene.sync()
        proxy.reset_next = 3  # as a server going down and coming up does
        proxy.cut()
        deadline = time.monotonic() + WAIT_SECONDS
        while proxy.accepted < 2:  # three attempts reset, the fourth goes through
            assert time.monotonic() < deadline, "the client gave up reconnecting"
            time.sleep(0.01)
        box.set_position(1, 2, 3)
        scene.sync()
        assert scene.client_id == me and proxy.reset_next == 0
        assert [n["position"] for n in patient.nodes(scene_name) if n["id"] == box.id] == [[1, 2, 3]]


def test_closing_on_purpose_does_not_come_back(patient, proxy, scene_name):
    scene = vp.connect(f"ws://127.0.0.1:{proxy.port}", scene=scene_name)
    vp.Box()
    scene.sync()
    scene.close()
    time.sleep(0.5)
    assert proxy.accepted == 1
