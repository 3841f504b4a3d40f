"""The app as a whole: every refusal, whatever raised it (a route's error, a path or
method no route has), answers with its HTTP status and the documented JSON body."""

import http.client
import json

import pytest
from websockets.sync.client import connect

from tests.conftest import WAIT_SECONDS


def answer(server, method: str, path: str) -> tuple[int, dict, dict]:
    connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=WAIT_SECONDS)
    try:
        connection.request(method, path)
        response = connection.getresponse()
        return response.status, dict(response.getheaders()), json.loads(response.read())
    finally:
        connection.close()


@pytest.mark.parametrize("method, path, status, code", [
    ("GET", "/api/no-such-route", 404, "not_found"),
    ("DELETE", "/api/health", 405, "method_not_allowed"),
    ("GET", "/api/scenes/no-such-scene", 404, "unknown_scene"),
    ("GET", "/api/assets/..%2F..%2Fserver%2Fcli.py", 403, "forbidden"),
    ("GET", "/api/recordings/no-such-recording/at?time=0", 404, "unknown_recording"),
])
def test_every_refusal_has_its_status_and_the_documented_body(server, method, path, status,
                                                               code):
    got, headers, body = answer(server, method, path)
    assert (got, body["code"]) == (status, code), body
    assert isinstance(body["message"], str) and body["message"]
    assert set(body) <= {"code", "message", "details"}
    if status == 405:
        assert headers["allow"] == "GET"  # what the path does take


def test_a_second_recording_of_a_scene_is_a_conflict(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        ws.recv(timeout=WAIT_SECONDS)  # hello: the scene runs
        status, _, started = answer(server, "POST", f"/api/scenes/{scene_name}/recordings")
        try:
            assert status == 201
            status, _, body = answer(server, "POST", f"/api/scenes/{scene_name}/recordings")
            assert (status, body["code"]) == (409, "recording_busy")
            assert started["id"] in body["message"]
        finally:
            answer(server, "POST", f"/api/recordings/{started['id']}/stop")
