"""GLTF parts: files, colours, mirrored right-hand parts and their envelopes."""

import pytest

from server.core.model.gltf_parts import (MAX_RECOLORS, AnthroPalm, AnthroThumb, GLTFPart,
                                          RoundFinger, RoundPalm, slot_direction)
from server.core.model.hands import AnthroHand, RoundHand
from server.core.model.part_figures import PALM_JOINT_GAP, round_palm_slots
from server.core.kit.errors import LimitExceeded, UnknownAsset


def test_hand_parts_are_the_manuals_classes_and_files(scene):
    round_parts = [type(p) for p in RoundHand(scene, "r").get_parts() if not p.type_name.startswith("Motor")]
    assert round_parts == [RoundPalm] + [RoundFinger] * 15
    anthro = [p for p in AnthroHand(scene, "a").get_parts() if not p.type_name.startswith("Motor")]
    assert [type(p) for p in anthro[:3]] == [AnthroPalm, AnthroThumb, RoundFinger]
    assert [p.mesh.url.rsplit("/", 1)[1] for p in anthro[2:5]] == [
        "round-finger-8.glb", "round-finger-5.glb", "round-tip.glb"]


def test_round_hands_are_recoloured_grey_and_right_ones_mirrored(scene):
    left, right = RoundHand(scene, "l", True), RoundHand(scene, "r", False)
    palm = left.get_parts()[0]
    assert palm.describe()["recolors"] == [[[0.0, 0.21, 1.0], [0.3, 0.3, 0.3], 0.01]]
    assert palm.geometry()["mirror"] is False and right.get_parts()[0].geometry()["mirror"] is True
    assert palm.geometry()["offset"] == [0.0, 0.7, 0.0]


def test_mesh_envelopes_are_a_few_dozen_hull_points_and_mirror_with_the_part(scene):
    left, right = RoundPalm(scene, "l", True, "round-palm.glb"), RoundPalm(scene, "r", False, "round-palm.glb")
    points = left.geometry()["points"]
    assert 20 <= len(points) <= 80
    mirrored = sorted((-x, y, z) for x, y, z in right.geometry()["points"])
    assert [c for p in mirrored for c in p] == pytest.approx(
        [c for p in sorted(tuple(p) for p in points) for c in p])
    ys = [p[1] for p in points]  # the file's box raised by length/2
    assert min(ys) == pytest.approx(-0.864 + 0.7, abs=0.02)
    clearance = [-max(sum((p[k] - position[k]) * u[k] for k in range(3)) for p in points)
                 for position, rotation, order in round_palm_slots(True, 1.4)[1:]
                 for u in [slot_direction(rotation, order)]]
    assert min(clearance) == pytest.approx(PALM_JOINT_GAP)  # the lowest finger's, exactly


@pytest.mark.parametrize("length", [0.001, 0.01, 0.05, 3.0, 1000.0])
def test_round_fingers_of_any_length_get_an_envelope_when_made(scene, length):
    finger = RoundFinger(scene, "f", "round-finger-8.glb", length)
    points = finger.geometry()["points"]
    assert len(points) >= 4
    finger.set_position((0, 5, 0))
    scene.tick(0.1)  # the tick describes the new part: nothing is left to fail there
    assert scene.failures == 0


def test_a_gltf_part_is_raised_by_half_its_length_and_has_no_slots_or_envelope(scene):
    part = GLTFPart(scene, "g", "round-palm.glb", 2)
    assert part.geometry() == {"kind": "mesh", "url": part.mesh.url, "offset": [0.0, 1.0, 0.0],
                               "mirror": False}
    assert part.slots == [] and part.constructor_args() == ["round-palm.glb", 2]


def test_a_missing_file_refuses_the_part_before_it_exists(scene):
    with pytest.raises(UnknownAsset):
        GLTFPart(scene, "g", "nowhere.glb")
    assert "g" not in scene.nodes


def test_recolours_are_kept_in_order_up_to_their_limit(scene):
    part = GLTFPart(scene, "g", "round-tip.glb")
    for k in range(MAX_RECOLORS):
        part.recolor("white", k, 0.1)
    with pytest.raises(LimitExceeded) as caught:
        part.recolor("white", "red")
    assert caught.value.details == {"limit": "recolors", "value": MAX_RECOLORS, "object": "g"}
    assert [r[1] for r in part.describe()["recolors"]] == list(range(MAX_RECOLORS))

