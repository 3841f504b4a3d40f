"""Mesh parts and round hands from Python: callbacks, recolours, safe filenames, parts as classes."""

from __future__ import annotations

import pytest

import virtual_prosthetics as vp


def test_gltf_part_callback_runs_once_made_and_recolor_reaches_the_scene(server, scene, scene_name):
    ready = []
    part = vp.GLTFPart("../assets/gltf/round-palm.glb", 1.4,
                       callback=lambda p: (ready.append(p), p.recolor([0, 0.21, 1], "red")))
    assert ready == [part]
    scene.sync()
    node = next(n for n in server.get(f"/api/scenes/{scene_name}/snapshot")["nodes"]
                if n["id"] == part.id)
    assert node["geometry"]["url"] == "/assets/gltf/round-palm.glb"
    assert node["recolors"] == [[[0.0, 0.21, 1.0], "red", 0.01]]


@pytest.mark.parametrize("filename", ["../../etc/passwd", "/etc/passwd", "round-palm.glb/..",
                                      "http://example.com/x.glb", "..%2fetc%2fpasswd.glb",
                                      "assets\\gltf\\round-palm.glb", "round-palm.glb\n"])
def test_forbidden_filenames_are_refused_and_nothing_is_made(server, scene, scene_name, filename):
    before = server.get(f"/api/scenes/{scene_name}/snapshot")["nodes"]
    with pytest.raises(vp.ServerError) as caught:
        vp.GLTFPart(filename, callback=lambda p: None)
    assert caught.value.code in ("forbidden", "bad_message")
    assert server.get(f"/api/scenes/{scene_name}/snapshot")["nodes"] == before


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
