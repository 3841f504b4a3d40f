"""The state folder: the server's key kept, client ids never handed out twice across
restarts, and a start that always succeeds (a broken server.json or a stray file set aside,
a folder that cannot be written reported)."""

from __future__ import annotations

import json
import stat
from pathlib import Path

import pytest

import virtual_prosthetics as vp
from server.core.protocol.operations import Operations
from server.core.scene.scene import Scene
from server.core.protocol.scene_document import encode_document, export_scene
from server.web.scenes.hub import Hubs
from server.web.storage.state_dir import CLIENT_BLOCK, StateDir
from tests.conftest import start_server, stop_server, unwritable


def test_the_key_and_the_ids_handed_out_outlive_the_server(tmp_path):
    first = Hubs(state=StateDir(tmp_path))
    ids = [first.new_client_id() for _ in range(3)]
    key = first.client_for("lab", None)[1]
    mode = stat.S_IMODE((tmp_path / "server.json").stat().st_mode)
    assert ids == ["c1", "c2", "c3"] and mode == 0o600
    second = Hubs(state=StateDir(tmp_path))  # after a restart, even kill -9
    assert int(second.new_client_id()[1:]) > 3
    client_id = key.partition(":")[0]
    assert second.client_for("lab", key) == (client_id, key)  # still this client's key
    saved = json.loads((tmp_path / "server.json").read_text())
    assert saved["clientsReserved"] >= CLIENT_BLOCK


def test_owners_a_document_brings_are_never_handed_out(tmp_path):
    hubs = Hubs(state=StateDir(tmp_path))
    hubs.reserve(["c2500", "demo", "c7"])
    assert hubs.new_client_id() == "c2501"
    assert int(Hubs(state=StateDir(tmp_path)).new_client_id()[1:]) > 2501


@pytest.mark.parametrize("text", ['{"secret": "", "clientsReserved": 1000}',
                                  '{"secret": "not hex at all", "clientsReserved": 1000}',
                                  '{"secret": "' + "ab" * 32 + '", "clientsReserved": -5}',
                                  '[1, 2]', '{"secret": ', "[" * 100_000])
def test_a_server_file_that_cannot_be_used_is_set_aside_and_a_new_key_made(tmp_path, text, caplog):
    (tmp_path / "server.json").write_text(text)
    state = StateDir(tmp_path)
    assert len(state.secret) == 32 and state.secret != b"" and state.clients_reserved >= 0
    assert (tmp_path / "server.json.unreadable-1").read_text() == text
    assert json.loads((tmp_path / "server.json").read_text())["secret"] == state.secret.hex()
    assert "a new key is made" in caplog.text


def test_files_in_scenes_that_no_scene_can_have_are_set_aside_once(tmp_path, caplog):
    scenes = tmp_path / "scenes"
    scenes.mkdir()
    odd = ["my lab.json", "lab.old.json", "x" * 65 + ".json", "my lab.journal"]
    for name in odd + ["lab.json", "notes.txt"]:
        (scenes / name).write_text("{}")
    state = StateDir(tmp_path)
    assert state.saved_scenes() == ["lab"]
    assert sorted(p.name for p in scenes.iterdir()) == sorted(
        [f"{name}.ignored-1" for name in odd] + ["lab.json", "notes.txt"])
    assert caplog.text.count("is no scene's file") == 4
    caplog.clear()
    StateDir(tmp_path)
    assert "is no scene's file" not in caplog.text  # once each


def test_ids_handed_out_when_the_server_file_cannot_be_written_still_work(tmp_path):
    hubs = Hubs(state=StateDir(tmp_path))
    (tmp_path / "server.json").unlink()
    (tmp_path / "server.json").mkdir()  # nothing can replace it now, not even as root
    (tmp_path / "server.json" / "x").write_text("")
    hubs.reserve([f"c{CLIENT_BLOCK * 3}"])
    assert hubs.new_client_id() == f"c{CLIENT_BLOCK * 3 + 1}"
    assert "cannot be written" in hubs.state.problems["server.json"]
    assert any("server.json" in problem for problem in hubs.problems())


def test_a_state_folder_that_cannot_be_made_is_reported_not_fatal(tmp_path):
    (tmp_path / "file").write_text("")
    state = StateDir(tmp_path / "file" / "state")  # below a file: no folder can be made
    assert state.saved_scenes() == [] and any("cannot be made" in p for p in
                                              state.problems.values())


# --- with a real server ------------------------------------------------------------------

def test_the_server_starts_whatever_its_state_folder_holds(tmp_path):
    """More saved scenes than it may run, and files no scene can have: it starts, runs
    none of them until used, sets the stray files aside."""
    state = tmp_path / "state"
    for k in range(7):
        saved_scene(state, f"s{k}", "c5")
    for odd in ("my lab.json", "lab.old.json", "x" * 70 + ".json"):
        (state / "scenes" / odd).write_text("{}")
    log = tmp_path / "server.log"
    server = start_server("--no-demo", "--state-dir", str(state), "--limit", "scenes=5", log=log)
    try:
        assert [s["name"] for s in server.get("/api/scenes")] == ["default"]
        listed = server.get("/api/scenes?saved=true")
        assert [s["name"] for s in listed if s["state"] == "saved"] == [f"s{k}" for k in range(7)]
        assert [n["id"] for n in server.nodes("s6")] == ["c5.arm"]  # opened when used
        assert log.read_text().count("is no scene's file") == 3
        assert sorted(p.name for p in (state / "scenes").iterdir() if "ignored" in p.name) == \
            sorted(f"{odd}.ignored-1" for odd in ("my lab.json", "lab.old.json", "x" * 70 + ".json"))
    finally:
        stop_server(server)


def test_a_state_folder_that_cannot_be_written_is_reported_and_connections_go_on(tmp_path):
    state = tmp_path / "state"
    saved_scene(state, "lab", "c5000")
    with unwritable(state):  # not even server.json can be made
        server = start_server("--no-demo", "--state-dir", str(state))
        try:
            health = server.get("/api/health")
            assert health["status"] == "degraded"
            assert any("server.json cannot be written" in p for p in health["problems"])
            with vp.connect(server.ws, scene="lab") as client:  # owners reserved: not noted
                assert int(client.client_id[1:]) > 5000
                vp.Box()
                client.sync()
        finally:
            stop_server(server)


def saved_scene(state: Path, name: str, owner: str) -> None:
    """A scene file with a kept robot of ``owner``."""
    scene = Scene(name)
    Operations(scene, owner).create(f"{owner}.arm", "Robot", [])
    scene.get(f"{owner}.arm").keep()
    (state / "scenes").mkdir(parents=True, exist_ok=True)
    (state / "scenes" / f"{name}.json").write_bytes(encode_document(export_scene(scene)))
    scene.close()
