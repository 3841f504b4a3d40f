"""The shared protocol vectors, replayed against a sans-I/O session and a real server.

Every server message seen here is also checked against the protocol's JSON Schema.
"""

from __future__ import annotations

import json

import pytest
from websockets.sync.client import connect

from server.core.protocol.messages import check_server_message
from server.core.scene.scene import Scene
from server.core.protocol.session import Session
from tests.conftest import WAIT_SECONDS

from .vectors import mismatch, steps, vector_files

FILES = vector_files()


def test_there_are_vectors():
    assert len(FILES) >= 4


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_vectors_against_a_session(path):
    scene = Scene("vectors")
    try:
        session = Session(scene, "c9")
        for number, (text, expected) in enumerate(steps(path, "c9")):
            answers = session.receive(text)
            for answer in answers:
                check_server_message(json.loads(json.dumps(answer)))
            problem = mismatch(expected, answers)
            assert problem is None, f"step {number}: {problem}"
    finally:
        scene.close()


def _answers_until_ping(ws, ping_id):
    answers = []
    while True:
        message = json.loads(ws.recv(timeout=WAIT_SECONDS))
        check_server_message(message)
        if message["op"] == "ok" and message["id"] == ping_id:
            return answers
        if message["op"] in ("ok", "error"):
            answers.append(message)


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_vectors_against_the_server(server, scene_name, path):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        hello = json.loads(ws.recv(timeout=WAIT_SECONDS))
        check_server_message(hello)
        for number, (text, expected) in enumerate(steps(path, hello["client"])):
            ws.send(text)
            ping_id = 10_000 + number
            ws.send(json.dumps({"op": "ping", "id": ping_id}))
            problem = mismatch(expected, _answers_until_ping(ws, ping_id))
            assert problem is None, f"step {number}: {problem}"
