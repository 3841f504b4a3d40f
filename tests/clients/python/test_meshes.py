"""Mesh parts and round hands from Python: callbacks, recolours, safe filenames, parts as classes."""

from __future__ import annotations

import math

import pytest
import trimesh

import virtual_prosthetics as vp


def test_gltf_part_callback_runs_once_made_and_recolor_reaches_the_scene(server, scene, scene_name):
    ready = []
    part = vp.GLTFPart("../assets/gltf/round-palm.glb", 1.4,
                       callback=lambda p: (ready.append(p), p.recolor([0, 0.21, 1], "red")))
    assert ready == [part]
    scene.sync()
    node = next(n for n in server.nodes(scene_name)
                if n["id"] == part.id)
    assert node["geometry"]["url"] == "/assets/gltf/round-palm.glb"
    assert node["recolors"] == [[[0.0, 0.21, 1.0], "red", 0.01]]


@pytest.mark.parametrize("filename", ["../../etc/passwd", "/etc/passwd", "round-palm.glb/..",
                                      "http://example.com/x.glb", "..%2fetc%2fpasswd.glb",
                                      "assets\\gltf\\round-palm.glb", "round-palm.glb\n"])
def test_forbidden_filenames_are_refused_and_nothing_is_made(server, scene, scene_name, filename):
    before = server.nodes(scene_name)
    with pytest.raises(vp.ServerError) as caught:
        vp.GLTFPart(filename, callback=lambda p: None)
    assert caught.value.code in ("forbidden", "bad_message")
    assert server.nodes(scene_name) == before


def test_a_missing_mesh_file_is_an_unknown_asset(scene):
    with pytest.raises(vp.ServerError) as caught:
        vp.RoundFinger("no-such-finger.glb", callback=lambda p: None)
    assert caught.value.code == "unknown_asset" and "round-palm.glb" in caught.value.message


def test_round_hand_parts_are_the_manuals_classes(scene):
    hand = vp.AnthroHand(False)
    scene.sync()
    parts = [type(p) for p in hand.get_parts() if not isinstance(p, vp.Motor)]
    assert parts[:3] == [vp.AnthroPalm, vp.AnthroThumb, vp.RoundFinger]
    assert len(hand.get_motors()) == 22 and len(vp.RoundHand().get_motors()) == 20


def test_an_uploaded_glb_makes_mesh_parts_in_any_scene(server, scene, scene_name, tmp_path):
    ball = trimesh.creation.icosphere(2, 0.4)
    path = tmp_path / "ball.glb"
    path.write_bytes(ball.export(file_type="glb"))
    name = vp.upload_asset(path)
    assert vp.upload_asset(path.read_bytes()) == name  # the same bytes, the same name
    decoration = vp.GLTFPart(name, 0.8, callback=lambda p: None)
    finger = vp.RoundFinger(name, 0.8, callback=lambda p: None)  # physical: an envelope
    finger.set_position(3, 1, 0)
    sensor = vp.Sensor()
    sensor.set_position(3, 3, 0)
    sensor.set_rotation(math.pi, 0, 0)
    nodes = {n["id"]: n for n in server.nodes(scene_name)}
    assert nodes[decoration.id]["geometry"]["url"] == f"/api/assets/{name}"
    assert 20 <= len(nodes[finger.id]["geometry"]["points"]) <= 80
    top = 1 + 0.4 + ball.vertices[:, 1].max()  # the mesh is raised by length/2 = 0.4
    assert sensor.sense_distance() == pytest.approx(3 - top, abs=1e-6)


def test_uploads_that_are_not_meshes_are_refused_with_the_reason(scene):
    with pytest.raises(vp.ServerError) as caught:
        vp.upload_asset(b"just some bytes")
    assert caught.value.code == "bad_asset" and "neither GLB nor glTF" in caught.value.message
