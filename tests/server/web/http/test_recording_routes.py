"""Recordings over REST: a scene with two hands and a watched sensor recorded while a
client moves them; the MCAP file, read with the ``mcap`` reader, holds every frame, request
and reading with its time. Bad ids, a second recording and an early download are refused."""

import io
import json
import urllib.error
import urllib.request

import pytest
from mcap.reader import make_reader
from websockets.sync.client import connect
from tests.conftest import WAIT_SECONDS

from ..ws_requests import request_all, wait_ticks


def _refused(call, status, code):
    with pytest.raises(urllib.error.HTTPError) as refused:
        call()
    assert refused.value.code == status
    body = json.loads(refused.value.read())
    assert body["code"] == code
    return body


def _send_and_collect(ws, text, frames):
    """Send one request; the frames that come before its answer go to ``frames``."""
    ws.send(text)
    sent = json.loads(text)["id"]
    while True:
        message = json.loads(ws.recv(timeout=WAIT_SECONDS))
        if message["op"] == "frame":
            frames.append(message)
        elif message["op"] in ("ok", "error") and message.get("id") == sent:
            assert message["op"] == "ok", message
            return


def _scene_with_two_hands_and_a_watched_sensor(ws, client):
    left, right, sensor = f"{client}.left", f"{client}.right", f"{client}.s"
    request_all(ws, [
        {"op": "create", "object": left, "type": "EdgedHand", "args": [True]},
        {"op": "create", "object": right, "type": "RoundHand", "args": [False]},
        {"op": "call", "object": right, "method": "setPosition", "args": [6, 0, 0]},
        {"op": "create", "object": sensor, "type": "Sensor"},
        {"op": "call", "object": sensor, "method": "setPosition", "args": [3, 6, 0]},
        {"op": "call", "object": sensor, "method": "setRotation", "args": [3.14159, 0, 0]},
        {"op": "call", "object": sensor, "method": "watch"},
    ])
    return left, right, sensor


def test_a_recording_holds_every_frame_request_and_reading_with_its_time(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        client = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
        left, right, sensor = _scene_with_two_hands_and_a_watched_sensor(ws, client)
        wait_ticks(ws)
        status, started = server.post(f"/api/scenes/{scene_name}/recordings")
        assert status == 201 and started["scene"] == scene_name
        texts, seen = [], []
        for k in range(40):  # the right hand flexes under the sensor's beam, then back
            texts.append(json.dumps({"op": "call", "object": right, "method": "setPosition",
                                     "args": [6 - 3 * min(k, 40 - k) / 20, 0, 0], "id": 10 + k}))
            _send_and_collect(ws, texts[-1], seen)
            # a tick at every place (a loaded machine's few ticks all fell where the hand
            # was not under the beam: every reading the same)
            wait_ticks(ws, 1)
            texts.append(json.dumps({"op": "call", "object": left, "method": "flexFingers",
                                     "args": [k / 40], "id": 100 + k}))
            _send_and_collect(ws, texts[-1], seen)
        wait_ticks(ws, 3)
        _, stopped = server.post(f"/api/recordings/{started['id']}/stop")
    assert stopped["id"] == started["id"] and stopped["stopped"] == "stopped"
    listed = {r["id"]: r for r in server.get("/api/recordings")}[started["id"]]
    assert listed["state"] == "stopped" and listed["scene"] == scene_name
    assert listed["messages"]["/vp/requests"] == len(texts)
    with urllib.request.urlopen(f"{server.http}/api/recordings/{started['id']}", timeout=WAIT_SECONDS) as answer:
        data = answer.read()
    assert len(data) == listed["bytes"]
    by_topic = {}
    reader = make_reader(io.BytesIO(data))
    for _, channel, message in reader.iter_messages():
        by_topic.setdefault(channel.topic, []).append((message.log_time, json.loads(message.data)))
    start_ns, snapshot = by_topic["/vp/snapshot"][0]
    assert {n["id"] for n in snapshot["nodes"]} >= {left, right, sensor}

    def scene_time(log_time):
        return snapshot["time"] + (log_time - start_ns) / 1e9

    frames = {}
    for log_time, tick in by_topic["/vp/ticks"]:
        for message in tick["messages"]:
            if message["op"] == "frame":
                assert message["time"] == pytest.approx(scene_time(log_time), abs=1e-6)
                frames[message["seq"]] = message
    seqs = sorted(frames)
    assert seqs == list(range(seqs[0], seqs[-1] + 1))  # every tick, none missing
    assert seqs[0] == snapshot["seq"] + 1
    assert {f["seq"] for f in seen if f["seq"] > snapshot["seq"]} <= set(frames)  # what the client got
    assert [r["text"] for _, r in by_topic["/vp/requests"]] == texts
    assert {r["client"] for _, r in by_topic["/vp/requests"]} == {client}
    readings = by_topic[f"/sensors/{sensor}"]
    carried = [(scene_time(t), f) for t, tick in by_topic["/vp/ticks"] for f in tick["messages"]
               if sensor in f.get("sensors", {})]
    assert len(readings) == len(carried) and len({r["distance"] for _, r in readings}) > 1
    for (log_time, reading), (time, frame) in zip(readings, carried):
        assert scene_time(log_time) == pytest.approx(time) and reading == frame["sensors"][sensor]
    base = f"/api/recordings/{started['id']}"
    end = server.get(f"{base}/at?time=1000000")
    assert end["time"] == end["duration"] == pytest.approx(listed["seconds"])
    assert [m["op"] for m in end["messages"]][0] == "snapshot"
    window = server.get(f"{base}/ticks?after=0&until={end['duration']}")["ticks"]
    assert [m["seq"] for _, tick in window for m in tick if m["op"] == "frame"] == seqs  # each, in order
    assert [t for t, _ in window] == sorted(t for t, _ in window) and window[-1][0] == end["duration"]
    _refused(lambda: server.get(f"{base}/ticks?after=0&until=11"), 400, "out_of_range")
    _, again = server.post(f"/api/recordings/{started['id']}/resimulate")  # kinematic: exactly
    assert (again["ticks"], again["requests"]) == (len(frames), len(texts))
    assert again["ticksDiffering"] == 0, again["differences"][:3]


def test_one_recording_at_a_time_and_none_downloaded_before_it_stops(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}"):
        _, started = server.post(f"/api/scenes/{scene_name}/recordings")
        busy = _refused(lambda: server.post(f"/api/scenes/{scene_name}/recordings"), 409, "recording_busy")
        assert started["id"] in busy["message"]
        _refused(lambda: urllib.request.urlopen(f"{server.http}/api/recordings/{started['id']}"),
                 409, "recording_busy")
        assert {r["id"]: r for r in server.get("/api/recordings")}[started["id"]]["state"] == "recording"
        server.post(f"/api/recordings/{started['id']}/stop")
        _, again = server.post(f"/api/recordings/{started['id']}/stop")  # stopped already: as it is
        assert again["state"] == "stopped"


@pytest.mark.parametrize("path", ["/api/recordings/nothing-here", "/api/recordings/..server.json",
                                  "/api/recordings/default-20260101T000000Z-abcd"])
def test_unknown_recordings_are_refused_by_name(server, path):
    body = _refused(lambda: server.get(path), 404, "unknown_recording")
    assert path.rsplit("/", 1)[1][:20] in body["message"]
