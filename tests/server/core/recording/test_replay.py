"""A recording read back: the scene at any time is what it was then (a mirror fed the
replay's snapshot and folded frame equals one fed the live scene's snapshot), and the
changes between two times bring one time's scene to the other's."""

import io

import pytest
from virtual_prosthetics.mirror import Mirror

from server.core.model.hands import EdgedHand
from server.core.model.parts import Ball
from server.core.recording.mcap_recorder import SNAPSHOT_EVERY, Recorder, RecordingLimits
from server.core.recording.replay import Replay, fold

TICK = 1 / 60
WALL = 1_700_000_000_000_000_000


def _recorded(scene, seconds):
    """Record a hand flexing and a ball coming and going; the live snapshots by tick time."""
    hand = EdgedHand(scene, "h", True)
    stream = io.BytesIO()
    recorder = Recorder(stream, scene, WALL, RecordingLimits(1 << 30, 3600))
    start, live = scene.time, {}
    for k in range(round(seconds / TICK)):
        hand.flex_fingers((k % 90) / 90)
        hand.set_position((k / 100, 0, 0))
        if k == 200:
            Ball(scene, "ball", 0.4).set_position((1, 2, 3))
        if k == 500:
            scene.delete(scene.nodes["ball"])
        recorder.tick(scene.tick(TICK), scene)
        live[scene.time - start] = scene.snapshot()
    recorder.finish("stopped", scene)
    return Replay(io.BytesIO(stream.getvalue())), live


def _state(messages):
    mirror = Mirror()
    for message in messages:
        mirror.apply(message)
    return {i: (n["position"], n["quaternion"], n.get("angle")) for i, n in mirror.nodes.items()}


def test_the_scene_at_any_time_is_what_it_was_then(scene):
    replay, live = _recorded(scene, 12)
    assert replay.duration == pytest.approx(12, abs=2 * TICK)
    times = sorted(live)
    for t in (times[0], times[150], times[250], SNAPSHOT_EVERY, times[299], times[300], 7.77,
              times[600], times[-1]):
        messages = replay.at(t)
        assert [m["op"] for m in messages][:1] == ["snapshot"] and \
            sum(m["op"] == "frame" for m in messages) <= 1 + sum(m["op"] != "frame" for m in messages)
        then = max(k for k in times if k <= t)  # between ticks: as the last tick left it
        assert _state(messages) == _state([live[then]]), t


def test_changes_between_two_times_bring_one_scene_to_the_other(scene):
    replay, live = _recorded(scene, 9)
    times = sorted(live)
    for a, b in ((times[10], times[400]), (times[190], times[210]), (times[490], times[510])):
        assert _state(replay.at(a) + replay.between(a, b)) == _state([live[b]]), (a, b)
    assert replay.between(times[50], times[50]) == []
    assert replay.ticks_after(times[10], 3) == pytest.approx(times[11:14], abs=1e-6)


def test_fold_keeps_structure_in_order_and_merges_frames():
    frames = [{"op": "frame", "seq": 1, "time": 0.1, "poses": {"a": [1, 0, 0, 0, 0, 0, 1]}},
              {"op": "frame", "seq": 2, "time": 0.2, "poses": {"b": [2, 0, 0, 0, 0, 0, 1]}},
              {"op": "added", "seq": 3, "nodes": []},
              {"op": "frame", "seq": 3, "time": 0.3, "poses": {"a": [3, 0, 0, 0, 0, 0, 1]}}]
    folded = fold(frames)
    assert [m["op"] for m in folded] == ["frame", "added", "frame"]
    assert folded[0]["seq"] == 2 and set(folded[0]["poses"]) == {"a", "b"}
