"""Recording from Python: a script records its own trial and keeps the file."""

from __future__ import annotations

import io
import json

import pytest
from mcap.reader import make_reader

import virtual_prosthetics as vp


def test_a_script_records_its_trial_and_saves_the_file(scene, tmp_path):
    hand = vp.EdgedHand(True)
    sensor = vp.Sensor()
    sensor.set_position(0, 6, 0)
    sensor.set_rotation(3.14159, 0, 0)
    sensor.watch()
    rec = vp.start_recording()
    for k in range(30):
        hand.flex_fingers(k / 30)
        scene.sync()
    summary = rec.stop()
    assert summary["stopped"] == "stopped" and summary["requests"] >= 30 and summary["ticks"] > 0
    path = rec.save(tmp_path / "trial.mcap")
    topics = {}
    for _, channel, message in make_reader(io.BytesIO(path.read_bytes())).iter_messages():
        topics.setdefault(channel.topic, []).append(json.loads(message.data))
    flexes = [r for r in topics["/vp/requests"] if '"flexFingers"' in r["text"]]
    assert len(flexes) == 30 and {r["client"] for r in flexes} == {scene.client_id}
    assert f"/sensors/{sensor.id}" in topics and topics["/scene"]


def test_a_second_recording_of_the_scene_is_refused_while_one_runs(scene):
    rec = vp.start_recording()
    with pytest.raises(vp.ServerError) as refused:
        vp.start_recording()
    assert refused.value.code == "recording_busy" and rec.id in refused.value.message
    rec.stop()


def test_the_scene_calls_start_and_stop_a_recording_and_a_viewer_may_not(server, scene, scene_name):
    rec = vp.start_recording()  # startRecording over the WebSocket: no token, no REST
    listed = {r["id"]: r for r in scene_list(server)}
    assert listed[rec.id]["state"] == "recording" and listed[rec.id]["scene"] == scene_name
    viewer = vp.Session(server.ws, scene=scene_name, role="viewer")  # (not made the current one)
    try:
        with pytest.raises(vp.ServerError) as refused:
            vp.stop_recording(viewer)
        assert refused.value.code == "forbidden"
    finally:
        viewer.close()
    summary = vp.stop_recording(scene)
    assert summary["id"] == rec.id and summary["stopped"] == "stopped"
    assert {r["id"]: r for r in scene_list(server)}[rec.id]["state"] == "stopped"
    with pytest.raises(vp.ServerError) as refused:
        vp.stop_recording(scene)
    assert refused.value.code == "unknown_recording"


def scene_list(server):
    return server.get("/api/recordings")
