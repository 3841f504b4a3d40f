"""A hand's grip as the tasks use it: the server's grip map, a file's override, and the
hand's layout palm down, checked against the server's own geometry."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import virtual_prosthetics as vp
from server.core.model.hands import EdgedHand
from server.core.scene.scene import Scene
from tests.clients.python.tasks.gripper import three_digits
from virtual_prosthetics.tasks.grip import hand_grip, read_grip_map
from virtual_prosthetics.tasks.scale import HUMAN_HAND


def test_a_10_hand_lies_palm_down_where_the_server_puts_its_parts(scene):
    grip = hand_grip(vp.EdgedHand(True))
    layout = grip.layout
    # the server's own geometry, the hand turned as the layout says
    world = Scene("layout")
    hand = EdgedHand(world, "h", True)
    hand.set_quaternion(layout.quaternion)
    hand.flex_fingers(0)
    hand.spread_finger(0, -1)  # its preshape: the thumb turned back, -(-1)
    world.tick(1 / 60)
    boxes = {part.id: world.bodies.physics.parts.aabb(part.id) for part in hand.get_parts() if part.physical}
    palm = boxes[hand.get_parts()[0].id]
    lowest = min(box[0][1] for box in boxes.values())
    ahead = min(box[0][2] for box in boxes.values())
    assert layout.palm_below == pytest.approx(-palm[0][1], abs=0.02)
    assert layout.lowest == pytest.approx(-lowest, abs=0.02)
    assert layout.palm_end == pytest.approx(palm[0][2], abs=0.02)
    assert layout.length == pytest.approx(palm[1][2] - ahead, abs=0.03)
    assert layout.length * vp.get_physics()["unit"] == pytest.approx(HUMAN_HAND, abs=0.005)
    assert layout.thumb_side == 1.0  # the thumb lies towards +x
    world.close()
    # palm down, fingers along -z: the turn the tasks gave the 1.0 hands by name
    assert np.allclose(layout.quaternion, (-math.sin(math.pi / 4), 0, 0, math.cos(math.pi / 4)), atol=0.03)


def test_a_gripper_faces_down_and_grasps_below_its_palm(scene):
    grip = hand_grip(three_digits(scene))
    assert len(grip.digits) == 3 and grip.digits[grip.opposing].tip is not None
    layout = grip.layout
    assert layout.grasp[1] < -layout.palm_below  # where its tips meet: below the palm
    assert layout.lowest > layout.palm_below     # its digits hang below it
    pinch = grip.nearest(2)  # the opposing digit and the one nearest it
    assert grip.opposing in pinch and len(pinch) == 2 and grip.nearest(None) == [0, 1, 2]


def test_a_grip_map_file_names_motors_by_index_or_name(scene, tmp_path):
    robot = three_digits(scene)
    path = tmp_path / "grip.json"
    path.write_text(json.dumps({"digits": [
        {"opposes": True, "motors": [{"name": "thumb base", "open": 0.1, "closed": 0.9}]},
        {"motors": [{"index": 2, "closed": -0.9}, {"name": "left middle", "closed": -0.5}]}]}))
    grip = hand_grip(robot, read_grip_map(path))
    assert [(m.index, m.open, m.closed) for m in grip.digits[0].motors] == [(0, 0.1, 0.9)]
    assert [(m.index, m.open, m.closed) for m in grip.digits[1].motors] == [(2, 0.0, -0.9), (3, 0.0, -0.5)]
    assert grip.opposing == 0
    assert grip.angles({0: 0.5, 1: 1.0})[:4] == [pytest.approx(0.5), None, -0.9, -0.5]
    assert grip.layout == hand_grip(robot).layout  # the frame stays the derived one


@pytest.mark.parametrize("content, said", [
    ("{", "grip map"),
    ('{"digits": []}', "at least one digit"),
    ('{"digits": [{"motors": [{"index": 0}]}]}', 'each motor needs "closed"'),
])
def test_a_grip_map_file_that_is_wrong_says_what(tmp_path, content, said):
    path = tmp_path / "grip.json"
    path.write_text(content)
    with pytest.raises(ValueError, match=said):
        read_grip_map(path)


@pytest.mark.parametrize("motor, said", [({"index": 12}, "not one of the robot's 0-5"),
                                         ({"name": "wrist"}, "no motor named 'wrist'")])
def test_a_grip_map_naming_a_motor_the_robot_lacks_is_refused(scene, tmp_path, motor, said):
    path = tmp_path / "grip.json"
    path.write_text(json.dumps({"digits": [{"motors": [{**motor, "closed": 1.0}]}]}))
    with pytest.raises(ValueError, match=said):
        hand_grip(three_digits(scene), read_grip_map(path))
