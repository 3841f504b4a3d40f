"""A scene's process makes its scene as its store saved it, with the server's own objects as
its setup makes them (in a real scene, with a real store on disk)."""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import pytest

from server.core.model.parts import Ball, Box
from server.core.protocol.scene_document import encode_document, export_scene
from server.core.scene.scene import Scene
from server.web.process.saving import SceneSaver
from server.web.process.scene_start import SERVER_OWNER, Animator, start_scene
from server.web.storage.scene_store import SceneStore


def _setup(made: list[str]) -> Callable[[Scene], Animator]:
    """A server's setup: one box of its own, and an animator that lifts it."""
    def setup(scene: Scene) -> Animator:
        box = Box(scene, f"{SERVER_OWNER}.box")
        box.set_position((0, 1, 0))
        made.append(box.id)
        return lambda scene, time: scene.nodes[f"{SERVER_OWNER}.box"].set_position((0, time, 0))
    return setup


def _saved(path: Path, *, server_box_at: float | None, client_ball: bool) -> SceneStore:
    """A store whose document holds the server's box (at that height) and a client's ball."""
    scene = Scene("lab")
    if server_box_at is not None:
        Box(scene, f"{SERVER_OWNER}.box").set_position((0, server_box_at, 0))
    if client_ball:
        Ball(scene, "alice.ball").set_position((2, 0.5, 0))
    path.write_bytes(encode_document(export_scene(scene)))
    scene.close()
    return SceneStore(path)


def _start(store: SceneStore | None, setup) -> tuple[Scene, Animator | None, list[str]]:
    scene = Scene("lab")
    animator, owners = start_scene(scene, store, SceneSaver(scene, store, lambda *_: None), setup)
    return scene, animator, owners


def test_a_new_scene_is_made_by_its_setup_and_the_animator_runs_it():
    made: list[str] = []
    scene, animator, owners = _start(None, _setup(made))
    assert made == [f"{SERVER_OWNER}.box"] and owners == []
    assert animator is not None
    animator(scene, 3.0)
    assert scene.nodes[f"{SERVER_OWNER}.box"].position[1] == pytest.approx(3.0)
    scene.close()


def test_saved_server_objects_keep_their_last_state_and_clients_may_come_back(tmp_path):
    store = _saved(tmp_path / "lab.json", server_box_at=5.0, client_ball=True)
    scene, animator, owners = _start(store, _setup([]))
    assert scene.nodes[f"{SERVER_OWNER}.box"].position[1] == pytest.approx(5.0)  # not the setup's 1
    assert "alice.ball" in scene.nodes and owners == ["alice"]
    assert animator is not None  # the setup still animates what the document restored
    scene.close()


def test_a_saved_scene_without_the_servers_objects_gets_them_from_the_setup(tmp_path):
    store = _saved(tmp_path / "lab.json", server_box_at=None, client_ball=True)
    made: list[str] = []
    scene, _, owners = _start(store, _setup(made))
    assert made and scene.nodes[f"{SERVER_OWNER}.box"].position[1] == pytest.approx(1.0)
    assert owners == ["alice"]
    scene.close()


def test_the_objects_of_a_setup_this_server_has_not_are_gone(tmp_path):
    store = _saved(tmp_path / "lab.json", server_box_at=5.0, client_ball=True)
    scene, animator, owners = _start(store, None)
    assert animator is None and owners == ["alice"]
    assert set(scene.nodes) == {"alice.ball"}
    scene.close()


def test_an_unreadable_document_is_set_aside_and_the_setup_makes_the_scene(tmp_path):
    path = tmp_path / "lab.json"
    path.write_bytes(b'{"format": "virtual-prosthetics-scene", "nodes": [{"id": 7}]}')
    made: list[str] = []
    scene, _, owners = _start(SceneStore(path), _setup(made))
    assert made and owners == [] and set(scene.nodes) == {f"{SERVER_OWNER}.box"}
    assert not path.exists() and any(tmp_path.iterdir())  # kept beside, under another name
    scene.close()
