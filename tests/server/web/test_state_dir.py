"""The state folder's files: written whole, read back, a broken one set aside (never
overwritten), the server's key kept, client ids never handed out twice across restarts."""

from __future__ import annotations

import json
import stat

from server.web.hub import Hubs
from server.web.state_dir import CLIENT_BLOCK, SceneStore, StateDir, write_atomically


def test_a_file_is_replaced_whole_and_no_partial_file_stays(tmp_path):
    target = tmp_path / "a.json"
    write_atomically(target, b"old")
    write_atomically(target, b"new")
    assert target.read_bytes() == b"new" and [p.name for p in tmp_path.iterdir()] == ["a.json"]


def test_a_scene_file_that_cannot_be_read_is_set_aside_not_lost(tmp_path, caplog):
    store = SceneStore(tmp_path / "lab.json")
    assert store.load() is None  # no file yet
    store.save(b'{"format": 1}')
    assert store.load() == {"format": 1}
    (tmp_path / "lab.json").write_bytes(b'{"format": "virtual-pro')  # cut short by hand
    assert store.load() is None
    assert (tmp_path / "lab.json.unreadable-1").read_bytes() == b'{"format": "virtual-pro'
    assert not (tmp_path / "lab.json").exists() and "lab.json" in caplog.text


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
