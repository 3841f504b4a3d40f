"""A scene's recordings in its own process: one at a time, the server told when one
starts and whatever ends it, the file whole and locked while it records; a folder that
cannot be written refused by name."""

import fcntl

import pytest

from server.core.kit.errors import RecordingBusy, StorageFailure, UnknownRecording
from server.core.kit.limits import DEFAULT
from server.core.model.parts import Ball
from server.core.recording.replay import Replay
from server.core.scene.scene import Scene
from server.web.recording.recording_file import SceneRecordings


@pytest.fixture
def scene():
    made = Scene("lab", DEFAULT.with_values(["recordingSeconds=1"]))
    yield made
    made.close()


class Told:
    """What the server would hear."""

    def __init__(self) -> None:
        self.started: list[str] = []
        self.ended: list[dict] = []


def recordings(scene, folder, told):
    return SceneRecordings(scene, folder, told.started.append, told.ended.append)


def test_a_clients_recording_is_told_started_and_ended_and_its_file_replays(scene, tmp_path):
    told = Told()
    kept = recordings(scene, tmp_path, told)
    recording_id = kept.start("c1")
    assert told.started == [recording_id] and recording_id.startswith("lab-")
    with pytest.raises(RecordingBusy):
        kept.start("c2")
    path = kept.current.path
    with pytest.raises(BlockingIOError), open(path, "rb") as other:  # locked while it records
        fcntl.flock(other, fcntl.LOCK_EX | fcntl.LOCK_NB)
    Ball(scene, "c1.b", 0.2)
    kept.tick(scene.tick(1 / 60))
    summary = kept.stop()
    assert told.ended == [summary] and summary["id"] == recording_id and kept.current is None
    with open(path, "rb") as stream:
        replay = Replay(stream)
        added = [m for m in replay.at(replay.duration) if m["op"] == "added"]
    assert [n["id"] for m in added for n in m["nodes"]] == ["c1.b"] and summary["ticks"] == 1
    with pytest.raises(UnknownRecording):
        kept.stop()


def test_a_limit_ends_a_recording_and_the_server_hears_why(scene, tmp_path):
    told = Told()
    kept = recordings(scene, tmp_path, told)
    kept.start("c1")
    for _ in range(90):  # a second and a half of scene time; the limit is one
        kept.tick(scene.tick(1 / 60))
    assert kept.current is None and len(told.ended) == 1
    assert "1 s" in told.ended[0]["stopped"]


def test_a_server_without_a_folder_or_with_one_it_cannot_write_refuses(scene, tmp_path):
    with pytest.raises(StorageFailure, match="keeps no recordings"):
        recordings(scene, None, Told()).start("c1")
    not_a_folder = tmp_path / "a-file"
    not_a_folder.write_text("")
    with pytest.raises(StorageFailure, match="cannot be written"):
        recordings(scene, not_a_folder, Told()).begin("r1", not_a_folder / "r1.mcap")
