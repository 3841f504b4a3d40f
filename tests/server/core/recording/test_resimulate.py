"""A recording run again: in kinematic mode every tick comes out as recorded; a request
changed in the file shows as differences from the tick it was applied in, naming what
moved differently."""

import io
import json

from mcap.reader import make_reader
from mcap.writer import Writer

from server.core.protocol.session import Session
from server.core.recording.mcap_recorder import Recorder, RecordingLimits
from server.core.recording.resimulate import resimulate
from server.core.scene.scene import Scene

TICK = 1 / 60


def _trial(scene):
    """A client makes two hands and a watched sensor, then (recorded) moves them for 2 s;
    the recording's bytes. Requests and ticks interleave as in a scene's process."""
    client = Session(scene, "c1")
    for op in ({"op": "create", "object": "c1.l", "type": "EdgedHand", "args": [True]},
               {"op": "create", "object": "c1.r", "type": "AnthroHand", "args": [False]},
               {"op": "call", "object": "c1.r", "method": "setPosition", "args": [6, 0, 0]},
               {"op": "create", "object": "c1.s", "type": "Sensor"},
               {"op": "call", "object": "c1.s", "method": "setPosition", "args": [3, 6, 0]},
               {"op": "call", "object": "c1.s", "method": "setRotation", "args": [3.14159, 0, 0]},
               {"op": "call", "object": "c1.s", "method": "watch"}):
        client.receive(json.dumps(op))
    scene.tick(TICK)
    stream = io.BytesIO()
    recorder = Recorder(stream, scene, 1_700_000_000_000_000_000, RecordingLimits(1 << 30, 3600))
    for k in range(120):
        texts = [json.dumps({"op": "call", "object": "c1.r", "method": "setPosition",
                             "args": [6 - 3 * min(k, 120 - k) / 60, 0, 0]}),
                 json.dumps({"op": "call", "object": "c1.l", "method": "flexFingers", "args": [k / 120]})]
        for text in texts[:1 + k % 2]:
            recorder.request("c1", text, scene.time)
            client.receive(text)
        recorder.tick(scene.tick(TICK), scene)
    recorder.finish("stopped", scene)
    return stream.getvalue()


def test_a_kinematic_recording_runs_again_with_no_difference(scene):
    data = _trial(scene)
    fresh = Scene("again")
    try:
        report = resimulate(io.BytesIO(data), fresh)
    finally:
        fresh.close()
    assert report["ticks"] == 120 and report["requests"] == 180
    assert report["ticksDiffering"] == 0 and report["differences"] == []


def test_a_changed_request_shows_where_the_run_differs(scene):
    data = _edited(_trial(scene), f'"args": [{41 / 120}]', '"args": [0.9]')  # the flex of k = 41
    fresh = Scene("again")
    try:
        report = resimulate(io.BytesIO(data), fresh)
    finally:
        fresh.close()
    first = report["differences"][0]
    assert first["tick"] == 42 and first["field"] == "angles" and first["id"] == "c1.l"  # its tick
    assert report["ticksDiffering"] >= 1 and {d["field"] for d in report["differences"]} <= {"angles", "sensors", "contacts", "poses"}


def _edited(data, old, new):
    """The recording with the one request whose text has ``old`` changed to ``new``."""
    out = io.BytesIO()
    writer = Writer(out)
    writer.start()
    reader = make_reader(io.BytesIO(data))
    schemas, channels, edits = {}, {}, 0
    for schema, channel, message in reader.iter_messages(log_time_order=False):
        if schema.id not in schemas:
            schemas[schema.id] = writer.register_schema(schema.name, schema.encoding, schema.data)
        if channel.id not in channels:
            channels[channel.id] = writer.register_channel(channel.topic, channel.message_encoding, schemas[schema.id])
        payload = message.data
        if channel.topic == "/vp/requests" and old in json.loads(payload)["text"]:
            request = json.loads(payload)
            payload = json.dumps({**request, "text": request["text"].replace(old, new)}).encode()
            edits += 1
        writer.add_message(channels[channel.id], message.log_time, payload, message.publish_time)
    writer.finish()
    assert edits == 1
    return out.getvalue()


def _closing_on_a_ball(scene, ticks_before):
    """A hand closes on a ball in dynamic mode, recorded from ``ticks_before`` ticks after
    the world was made; the recording's bytes."""
    client = Session(scene, "c1")
    for op in ({"op": "create", "object": "c1.h", "type": "EdgedHand", "args": [True]},
               {"op": "call", "object": "c1.h", "method": "setRotation", "args": [-1.5708, 0, 0]},
               {"op": "call", "object": "c1.h", "method": "setPosition", "args": [0, 2.2, 0]},
               {"op": "create", "object": "c1.b", "type": "Ball", "args": [0.6]},
               {"op": "call", "object": "c1.b", "method": "setPosition", "args": [0, 0.6, -1.2]},
               {"op": "call", "object": "scene", "method": "setPhysics", "args": ["dynamic"]}):
        client.receive(json.dumps(op))
    for _ in range(ticks_before):
        scene.tick(TICK)
    stream = io.BytesIO()
    recorder = Recorder(stream, scene, 1_700_000_000_000_000_000, RecordingLimits(1 << 30, 3600))
    for k in range(120):
        text = json.dumps({"op": "call", "object": "c1.h", "method": "flexFingers", "args": [-min(1.2, k / 60)]})
        recorder.request("c1", text, scene.time)
        client.receive(text)
        recorder.tick(scene.tick(TICK), scene)
    recorder.finish("stopped", scene)
    return stream.getvalue()


def _again(data, tolerance=0.0):
    fresh = Scene("again")
    try:
        return resimulate(io.BytesIO(data), fresh, tolerance)
    finally:
        fresh.close()


def test_a_dynamic_recording_from_a_world_just_made_runs_again_alike_and_the_same_every_time(scene):
    data = _closing_on_a_ball(scene, 0)
    report = _again(data)
    assert report["ticks"] == 120 and report["ticksDiffering"] <= 1  # its first tick's contacts
    assert all(d["tick"] == 1 for d in report["differences"])
    assert _again(data) == report


def test_a_dynamic_recording_begun_mid_motion_drifts_and_says_where(scene):
    report = _again(_closing_on_a_ball(scene, 60))
    assert report["ticksDiffering"] > 60
    assert {d["field"] for d in report["differences"]} & {"poses", "angles"}
