"""A task's world in the scene's units: objects at their real size, and a 1.0 hand at the
default unit a human hand's size."""

import math

import pytest

import virtual_prosthetics as vp
from server.core.model.hands import EdgedHand
from server.core.scene.scene import Scene
from virtual_prosthetics.tasks.scale import HUMAN_HAND, Scale


def test_the_scale_is_the_scenes_unit_and_lengths_go_both_ways(scene):
    vp.set_physics("dynamic", unit=0.01)
    scene.sync()
    scale = Scale.of(scene)
    assert scale.unit == pytest.approx(0.01) and scale.length(0.05) == pytest.approx(5.0)
    assert scale.metres(scale.length(0.123)) == pytest.approx(0.123)


def test_at_the_default_unit_a_10_hand_is_a_human_hands_size():
    scene = Scene("unit")
    hand = EdgedHand(scene, "h", True)
    hand.set_rotation(-math.pi / 2, 0, 0)
    hand.flex_fingers(0)  # straight and together
    hand.spread_fingers(0)
    scene.tick(1 / 60)
    boxes = [scene.bodies.physics.parts.aabb(part.id) for part in hand.get_parts() if part.physical]
    along = max(box[1][2] for box in boxes) - min(box[0][2] for box in boxes)
    assert along * scene.physics.unit == pytest.approx(HUMAN_HAND, abs=0.005)  # metres
    scene.close()
