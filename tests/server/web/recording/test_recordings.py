"""The recordings folder as the server finds it: files cut short, changed or not MCAP at
all are listed as damaged and every read of them is refused naming why (never a 500); a
symbolic link in the folder is no recording, whatever it points at."""

from __future__ import annotations

import json
import os
import random
import urllib.error
from pathlib import Path
from typing import Any, Iterator

import pytest
from websockets.sync.client import connect

from tests.conftest import WAIT_SECONDS, RunningServer, start_server, stop_server

from ..ws_requests import request_all, wait_ticks

SCENE = "rec"


@pytest.fixture(scope="module")
def recorded(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[RunningServer, Path, str]]:
    """A server with a state folder and one finished recording of a hand that moved."""
    state = tmp_path_factory.mktemp("state")
    server = start_server("--no-demo", "--state-dir", str(state))
    try:
        with connect(f"{server.ws}/ws?scene={SCENE}") as ws:
            me = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
            request_all(ws, [{"op": "create", "object": f"{me}.h", "type": "EdgedHand"}])
            _, started = server.post(f"/api/scenes/{SCENE}/recordings")
            for k in range(5):
                request_all(ws, [{"op": "call", "object": f"{me}.h", "method": "flexFingers",
                                  "args": [k / 5]}])
                wait_ticks(ws)
            server.post(f"/api/recordings/{started['id']}/stop")
        yield server, state / "recordings", started["id"]
    finally:
        stop_server(server)


def _refusal(server: RunningServer, path: str, post: bool = False) -> tuple[int, dict[str, Any]]:
    with pytest.raises(urllib.error.HTTPError) as refused:
        server.post(path) if post else server.get(path)
    return refused.value.code, json.loads(refused.value.read())


def _damage(kind: str, good: bytes) -> bytes:
    rng = random.Random(kind)
    if kind == "empty":
        return b""
    if kind == "truncated":
        return good[:len(good) // 2]
    if kind == "flipped":  # bytes changed inside its chunks: the summary still reads
        body = bytearray(good)
        for at in range(64, len(body) // 2, max(1, len(body) // 40)):
            body[at] ^= 0xFF
        return bytes(body)
    return rng.randbytes(len(good))  # random


@pytest.mark.parametrize("kind", ["empty", "truncated", "flipped", "random"])
def test_a_damaged_file_is_listed_so_and_every_read_of_it_is_refused_naming_why(recorded, kind):
    server, folder, good = recorded
    damaged = f"{SCENE}-20260101T000000Z-{['empty', 'truncated', 'flipped', 'random'].index(kind):04x}"
    (folder / f"{damaged}.mcap").write_bytes(_damage(kind, (folder / f"{good}.mcap").read_bytes()))
    listed = {r["id"]: r for r in server.get("/api/recordings")}
    assert listed[good]["state"] == "stopped"
    base = f"/api/recordings/{damaged}"
    for path, post in ((f"{base}/at?time=0.5", False), (f"{base}/ticks?after=0&until=1", False),
                       (f"{base}/resimulate", True)):
        status, body = _refusal(server, path, post)
        assert (status, body["code"]) == (422, "recording_damaged"), (path, body)
        assert damaged in body["message"] and body["details"]["recording"] == damaged
    if listed[damaged]["state"] == "damaged":  # a file whose summary reads is found out when read
        assert listed[damaged]["damage"]  # says what is wrong
    assert server.get(f"/api/recordings/{good}/at?time=0")["messages"]  # the good one still plays
    assert server.get("/api/health")["status"] == "ok"


def test_a_symbolic_link_in_the_folder_is_no_recording(recorded, tmp_path):
    server, folder, good = recorded
    secret = tmp_path / "secret.txt"
    secret.write_text("not for the server's callers")
    for name, target in (("lnk-20260101T000000Z-0001", secret),
                         ("lnk-20260101T000000Z-0002", folder / f"{good}.mcap")):
        link = folder / f"{name}.mcap"
        os.symlink(target, link)
        assert name not in {r["id"] for r in server.get("/api/recordings")}
        for path in (f"/api/recordings/{name}", f"/api/recordings/{name}/at"):
            status, body = _refusal(server, path)
            assert (status, body["code"]) == (404, "unknown_recording")
            assert "not for the server" not in json.dumps(body)


def test_past_its_limits_the_oldest_finished_recordings_make_room(tmp_path):
    # 150 recordings started and stopped kept 153 files: nothing bounded them
    server = start_server("--no-demo", "--state-dir", str(tmp_path), "--limit", "recordings=3")
    try:
        with connect(f"{server.ws}/ws?scene={SCENE}") as ws:
            ws.recv(timeout=WAIT_SECONDS)
            made = []
            for _ in range(5):
                _, started = server.post(f"/api/scenes/{SCENE}/recordings")
                made.append(started["id"])
                wait_ticks(ws)
                server.post(f"/api/recordings/{started['id']}/stop")
            kept = [r["id"] for r in server.get("/api/recordings")]
            assert sorted(kept) == sorted(made[-3:])  # the newest three
            _, running = server.post(f"/api/scenes/{SCENE}/recordings")  # one more: room made
            assert len(server.get("/api/recordings")) == 3
            server.post(f"/api/recordings/{running['id']}/stop")
    finally:
        stop_server(server)
