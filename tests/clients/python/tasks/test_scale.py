"""The hand figures the tasks predict are the server's, and a task's unit makes its hand human-sized."""

import math

import numpy as np
import pytest

from server.core.model.hands import AnthroHand, EdgedHand, RoundHand
from server.core.scene.scene import Scene
from virtual_prosthetics.tasks.scale import FIGURES, HUMAN_HAND, Scale

KINDS = {"edged": EdgedHand, "round": RoundHand, "anthro": AnthroHand}


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_each_hands_figures_are_where_the_server_puts_the_hand(kind):
    scene = Scene("figures")
    hand = KINDS[kind](scene, "h", True)
    hand.set_rotation(-math.pi / 2, 0, 0)
    hand.flex_fingers(0)
    hand.spread_fingers(0)
    scene.tick(1 / 60)
    parts = [part for part in hand.get_parts() if part.physical]
    boxes = {part.id: scene.bodies.physics.aabb(part.id) for part in parts}
    palm = next(part for part in parts if "Palm" in part.type_name)
    low = np.min([box[0] for box in boxes.values()], axis=0)
    palm_low, palm_high = boxes[palm.id]
    figures = FIGURES[kind]
    assert figures.length == pytest.approx(palm_high[2] - low[2], abs=0.01)
    assert figures.fingers_z == pytest.approx(palm_low[2], abs=0.01)
    assert figures.palm_x == pytest.approx((palm_low[0] + palm_high[0]) / 2, abs=0.01)
    assert figures.palm_below == pytest.approx(-palm_low[1], abs=0.01)
    thumb = np.max([box[1][0] for box in boxes.values()])  # the thumb reaches furthest in +x
    assert thumb * figures.thumb_side > palm_high[0]
    scene.close()


def test_a_tasks_unit_makes_its_hand_a_human_hands_size_on_the_server():
    scale = Scale.of("edged")
    scene = Scene("unit")
    scene.set_physics("kinematic", {"unit": scale.unit})
    hand = EdgedHand(scene, "h", True)
    hand.set_rotation(-math.pi / 2, 0, 0)
    hand.flex_fingers(0)  # straight and together
    hand.spread_fingers(0)
    scene.tick(1 / 60)
    boxes = [scene.bodies.physics.aabb(part.id) for part in hand.get_parts() if part.physical]
    along = max(box[1][2] for box in boxes) - min(box[0][2] for box in boxes)
    assert along * scene.physics.unit == pytest.approx(HUMAN_HAND, abs=0.005)  # metres
    assert scale.length(HUMAN_HAND) == pytest.approx(FIGURES["edged"].length)
    scene.close()
