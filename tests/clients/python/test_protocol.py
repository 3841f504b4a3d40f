"""The Python client's protocol core, driven without any socket; and its refusal of an
oversize request, compared with the real server's."""

from __future__ import annotations

import json

import pytest
import websockets.sync.client

import virtual_prosthetics as vp
from virtual_prosthetics.errors import ConnectionLost, ProtocolError, ServerError
from virtual_prosthetics.protocol import ProtocolCore


class Heard:
    def __init__(self) -> None:
        self.messages: list[dict] = []
        self.changes: list[dict] = []

    def core(self) -> ProtocolCore:
        return ProtocolCore(self.messages.append, self.changes.append)


def test_requests_get_increasing_ids_and_travel_without_bare_infinity():
    core = Heard().core()
    first = core.request({"op": "call", "object": "c1.1", "method": "setAngle", "args": ["NaN"]})
    second = core.request({"op": "ping"})
    assert (first.id, second.id) == (1, 2)
    assert json.loads(first.text) == {"op": "call", "object": "c1.1", "method": "setAngle",
                                      "args": ["NaN"], "id": 1}
    assert core.unanswered == {1, 2}
    with pytest.raises(ValueError):
        core.request({"op": "call", "args": [float("inf")]})  # must be encoded first


def test_a_waited_answer_is_kept_until_taken_and_its_changes_reach_the_mirror():
    heard = Heard()
    core = heard.core()
    request = core.request({"op": "ping"}, wait=True)
    core.receive(json.dumps({"op": "ok", "id": request.id, "result": {"seq": 3},
                             "changes": {"angles": {"c1.2": 0.5}}}))
    assert heard.changes == [{"angles": {"c1.2": 0.5}}]
    assert core.unanswered == set()
    assert core.result(request.id) == {"seq": 3}
    with pytest.raises(KeyError):
        core.result(request.id)


def test_an_error_nobody_waits_for_is_kept_for_the_next_call():
    core = Heard().core()
    request = core.request({"op": "delete", "object": "c1.9"})
    core.receive(json.dumps({"op": "error", "id": request.id, "code": "unknown_object",
                             "message": "no object c1.9", "request": "delete"}))
    error = core.take_deferred()
    assert isinstance(error, ServerError) and error.code == "unknown_object"
    assert core.take_deferred() is None


def test_a_waited_error_is_raised_by_result_not_kept():
    core = Heard().core()
    request = core.request({"op": "call"}, wait=True)
    core.receive(json.dumps({"op": "error", "id": request.id, "code": "wrong_type",
                             "message": "x", "request": "call"}))
    with pytest.raises(ServerError, match="wrong_type"):
        core.result(request.id)
    assert core.take_deferred() is None


def test_warnings_are_kept_once():
    core = Heard().core()
    request = core.request({"op": "call"})
    core.receive(json.dumps({"op": "ok", "id": request.id, "warnings": ["no slot 7"]}))
    assert core.take_warnings() == ["no slot 7"]
    assert core.take_warnings() == []


def test_frames_and_errors_without_id_go_to_on_message():
    heard = Heard()
    core = heard.core()
    core.receive('{"op": "frame", "seq": 1, "time": 0.1}')
    core.receive('{"op": "error", "id": null, "code": "bad_json", "message": "x", "request": null}')
    assert [m["op"] for m in heard.messages] == ["frame", "error"]
    assert core.take_deferred().code == "bad_json"


@pytest.mark.parametrize("text", ['{"op": "teleport"}', "[1, 2]", "not json", '{"no": "op"}'])
def test_unknown_messages_fail_loudly(text):
    with pytest.raises(ProtocolError):
        Heard().core().receive(text)


def test_hello_gives_the_key_to_come_back_and_a_reconnection_settles_the_unanswered():
    core = Heard().core()
    core.receive(json.dumps({"op": "hello", "client": "c3", "resume": "c3:abc",
                             "limits": {"leaveGraceSeconds": 10}}))
    assert (core.resume, core.grace) == ("c3:abc", 10.0)
    waited = core.request({"op": "call", "object": "c3.m", "method": "getAngle"}, wait=True)
    core.request({"op": "call", "object": "c3.m", "method": "setAngle", "args": [1]})
    core.reconnected()
    assert core.unanswered == set() and core.interrupted == {waited.id}
    lost = core.take_deferred()
    assert isinstance(lost, ConnectionLost) and "may or may not" in str(lost)
    assert core.take_deferred() is None and core.closed is None  # the conversation goes on


def test_a_request_over_the_servers_message_bytes_is_refused_at_once_as_the_server_refuses_it(
        server, scene):
    """Found: a request of more than 1 MiB was refused by the server without an id (it
    cannot read one from such a text), and the script waited its whole timeout. The
    client refuses it at once, with the server's code and details, and sends nothing."""
    texts: list[str] = []
    send = scene.connection._ws.send
    scene.connection._ws.send = lambda text: (texts.append(text), send(text))[1]
    caption = "x" * (1 << 20)
    with pytest.raises(ServerError) as raised:
        vp.set_caption(caption)
    assert texts == [] and raised.value.code == "too_large"
    with websockets.sync.client.connect(f"{server.ws}/ws?scene={scene.name}",
                                        max_size=None) as raw:
        raw.recv(), raw.recv()  # hello, snapshot
        raw.send(json.dumps({"op": "call", "object": "scene", "method": "setCaption",
                             "args": [caption], "id": 1}))
        refusal = next(m for m in iter(lambda: json.loads(raw.recv(timeout=30)), None)
                       if m["op"] == "error")
    assert (refusal["code"], refusal["details"]) == (raised.value.code, raised.value.details)
    vp.set_caption("fits")  # the connection carries on
    scene.sync()
    assert scene.read(lambda mirror: mirror.caption) == "fits"
