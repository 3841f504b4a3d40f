"""The recorder alone, fed by a scene in this process: snapshots to seek from, limits that
stop it cleanly with the reason, and a file the mcap reader reads whole."""

import io
import json

import pytest
from mcap.reader import make_reader

from server.core.model.hands import EdgedHand
from server.core.recording.mcap_recorder import SNAPSHOT_EVERY, Recorder, RecordingLimits

TICK = 1 / 60
WALL = 1_700_000_000_000_000_000


def _recorded(scene, limits, seconds):
    """Record ``seconds`` of a hand flexing; the recorder (finished) and the file's messages."""
    hand = EdgedHand(scene, "h", True)
    stream = io.BytesIO()
    recorder = Recorder(stream, scene, WALL, limits)
    for k in range(round(seconds / TICK)):
        hand.flex_fingers((k % 60) / 60)
        if recorder.tick(scene.tick(TICK), scene):
            break
    recorder.finish("stopped", scene)
    reader = make_reader(io.BytesIO(stream.getvalue()))
    return recorder, [(c.topic, m.log_time, json.loads(m.data)) for _, c, m in reader.iter_messages()]


def test_snapshots_come_every_few_seconds_of_scene_time(scene):
    recorder, messages = _recorded(scene, RecordingLimits(1 << 30, 3600), 12)
    snapshots = [(t, m) for topic, t, m in messages if topic == "/vp/snapshot"]
    assert [round((t - WALL) / 1e9, 3) for t, _ in snapshots] == pytest.approx(
        [0, SNAPSHOT_EVERY, 2 * SNAPSHOT_EVERY], abs=1.5 * TICK)  # the first tick at or past it
    assert all(m["op"] == "snapshot" and m["nodes"] for _, m in snapshots)
    assert recorder.counts["ticks"] == 12 * 60 and recorder.stopped == "stopped"


@pytest.mark.parametrize("limits, words", [
    (RecordingLimits(300_000, 3600), "300000 bytes"),
    (RecordingLimits(1 << 30, 2), "2 s of scene time"),
])
def test_a_limit_stops_the_recording_cleanly_and_says_which(scene, limits, words):
    recorder, messages = _recorded(scene, limits, 60)
    assert words in recorder.stopped and "--limit recording" in recorder.stopped
    ticks = [t for topic, t, _ in messages if topic == "/vp/ticks"]
    assert 0 < len(ticks) < 60 * 60  # stopped early, and what it holds reads whole
    if "seconds" in words:
        assert (ticks[-1] - WALL) / 1e9 == pytest.approx(2, abs=TICK)


def test_every_channels_schema_stands_alone_and_validates_what_was_recorded(scene):
    """A tool builds a validator from a channel's schema in the file: every reference in
    it resolves there (`#/$defs/changes/properties/angles` once pointed at nothing: every
    tick message raised PointerToNowhere), and the messages recorded match it."""
    import jsonschema

    scene.set_physics("dynamic")
    _, messages = _recorded(scene, RecordingLimits(1 << 30, 3600), 1)
    reader = make_reader(io.BytesIO(_file(scene)))
    schemas = {c.topic: json.loads(s.data) for s, c, _ in reader.iter_messages()}
    assert {"/vp/ticks", "/vp/snapshot"} <= schemas.keys()
    checked = 0
    for topic, _, message in messages:
        if topic in ("/vp/ticks", "/vp/snapshot"):
            jsonschema.Draft202012Validator(schemas[topic]).validate(message)
            checked += 1
    assert checked > 60


def _file(scene) -> bytes:
    stream = io.BytesIO()
    recorder = Recorder(stream, scene, WALL, RecordingLimits(1 << 30, 3600))
    recorder.tick(scene.tick(TICK), scene)
    recorder.finish("stopped", scene)
    return stream.getvalue()
