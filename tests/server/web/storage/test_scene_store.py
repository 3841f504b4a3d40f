"""A scene's files: the document and the journal that follows it."""

from __future__ import annotations

import json

from server.web.storage.scene_store import SceneStore, write_atomically


def test_a_file_is_replaced_whole_and_no_partial_file_stays(tmp_path):
    target = tmp_path / "a.json"
    write_atomically(target, b"old")
    write_atomically(target, b"new")
    assert target.read_bytes() == b"new" and [p.name for p in tmp_path.iterdir()] == ["a.json"]


def test_a_scene_file_that_cannot_be_read_is_set_aside_with_its_journal(tmp_path, caplog):
    store = SceneStore(tmp_path / "lab.json")
    assert store.load() is None  # no file yet
    store.save(b'{"format": 1}')
    assert store.load() == {"format": 1}
    (tmp_path / "lab.json").write_bytes(b'{"format": "virtual-pro')  # cut short by hand
    assert store.load() is None
    assert (tmp_path / "lab.json.unreadable-1").read_bytes() == b'{"format": "virtual-pro'
    assert (tmp_path / "lab.journal.unreadable-1").exists()
    assert not (tmp_path / "lab.json").exists() and "lab.json" in caplog.text


def test_the_journal_follows_its_document_and_starts_again_with_each_new_one(tmp_path):
    store = SceneStore(tmp_path / "lab.json")
    store.append(b'{"a": 1}\n')  # no document yet: the journal follows none
    store.append(b'{"a": 2}\n')
    again = SceneStore(tmp_path / "lab.json")
    assert again.load() is None and again.journal() == [b'{"a": 1}', b'{"a": 2}']
    store.save(b'{"doc": 1}')
    store.append(b'{"a": 3}\n')
    again = SceneStore(tmp_path / "lab.json")
    assert again.load() == {"doc": 1} and again.journal() == [b'{"a": 3}']


def test_a_journal_older_than_its_document_is_left_out(tmp_path):
    """A crash after the document was written, before the journal started again: the
    journal's lines are in the document already."""
    store = SceneStore(tmp_path / "lab.json")
    store.save(b'{"doc": 1}')
    store.append(b'{"a": 1}\n')
    write_atomically(tmp_path / "lab.json", b'{"doc": 2}')  # the newer document alone
    again = SceneStore(tmp_path / "lab.json")
    assert again.load() == {"doc": 2} and again.journal() == []
    again.append(b'{"b": 1}\n')  # a new journal after the newer document
    header = json.loads((tmp_path / "lab.journal").read_bytes().split(b"\n")[0])
    assert header["after"] == again._document
    assert SceneStore(tmp_path / "lab.json").load() and again.journal() == [b'{"b": 1}']


def test_after_a_replacement_that_could_not_be_saved_no_journal_is_replayed(tmp_path):
    store = SceneStore(tmp_path / "lab.json")
    store.save(b'{"doc": 1}')
    store.forget_journal()
    store.append(b'{"after the import": 1}\n')
    again = SceneStore(tmp_path / "lab.json")
    assert again.load() == {"doc": 1} and again.journal() == []
