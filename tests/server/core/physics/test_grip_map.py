"""A hand's grip map from its kinematics: the 1.0 hands as their manual flexes them, and
grippers designed here that no table knows."""

import json
import math
from pathlib import Path

import jsonschema

import numpy as np
import pytest

from server.core.model.hands import AnthroHand, EdgedHand, RoundHand
from server.core.model.motor import MotorX, Slider
from server.core.model.parts import Box, EdgedFinger, EdgedTip
from server.core.model.robot import Robot
from server.core.model.structure import structure_of

HANDS = {"edged": EdgedHand, "round": RoundHand, "anthro": AnthroHand}


def _indices(robot, motors):
    order = [m.id for m in robot.get_motors()]
    return [order.index(m["motor"]) for m in motors]


@pytest.mark.parametrize("kind", sorted(HANDS))
def test_a_10_hand_closes_each_finger_with_the_motors_its_manual_flexes(scene, kind):
    hand = HANDS[kind](scene, "h", True)
    found = hand.get_grip_map()
    digits = found["digits"]
    assert len(digits) == 5 and [d["opposes"] for d in digits] == [True] + [False] * 4  # the thumb
    for finger, digit in enumerate(digits):
        assert _indices(hand, digit["motors"]) == list(hand.flex_indices(finger))
        assert [m["index"] for m in digit["motors"]] == list(hand.flex_indices(finger))
        # flexFinger(i, a) sets its motors to -a: closing is towards -π/2
        assert all(m["closed"] == pytest.approx(-math.pi / 2, abs=0.1) for m in digit["motors"][1:])
    assert found["approach"] == pytest.approx([0, 0, -1], abs=0.02)  # the palm's side
    assert found["forward"] == pytest.approx([0, 1, 0], abs=0.06)    # the fingers' way
    assert found["palm"] == hand.get_parts()[0].id


def test_a_grip_map_is_what_the_schema_says_and_names_each_digits_parts(scene):
    hand = EdgedHand(scene, "h", True)
    found = hand.get_grip_map()
    schema = json.loads((Path(__file__).parents[4] / "protocol" / "schema" / "protocol.json").read_text())
    jsonschema.validate(found, {"$defs": schema["$defs"], "$ref": "#/$defs/gripMap"})
    thumb = found["digits"][0]
    assert thumb["parts"][-1] == thumb["tip"] and len(thumb["parts"]) == 3  # its segments
    assert hand.get_grip_map() == found  # (kept until the tree changes)


def test_the_edged_thumb_is_turned_back_towards_the_wrist_before_a_grasp(scene):
    hand = EdgedHand(scene, "h", True)
    [turn] = hand.get_grip_map()["digits"][0]["preshape"]
    # what the grasp task found by trial when it named hands (its spread motor at -1)
    assert (turn["index"], turn["closed"]) == (0, pytest.approx(-1.0))


def _digit(scene, robot, palm, name, at, turn):
    """MotorX, EdgedFinger, MotorX, EdgedTip on a slot of the palm at ``at``, turned."""
    slot = palm.add_slot(at)
    slot.set_rotation(*turn)
    parts = [MotorX(scene, f"{name}1", -1.2, 1.2, 0), EdgedFinger(scene, f"{name}f", 1.2),
             MotorX(scene, f"{name}2", -1.2, 1.2, 0), EdgedTip(scene, f"{name}t")]
    robot.add_chain(slot, *parts)
    return parts


def _gripper(scene):
    """A box palm with three digits pointing down: one on the -z side, two on the +z side."""
    robot, palm = Robot(scene, "g"), Box(scene, "palm", 2.4, 0.5, 2.4)
    robot.attach_chain(palm)
    down = math.pi  # a finger grows along its +y: turned half round x it points down
    _digit(scene, robot, palm, "t", (0, -0.25, -0.9), (down, 0, 0))
    _digit(scene, robot, palm, "a", (-0.6, -0.25, 0.9), (down, 0, 0))
    _digit(scene, robot, palm, "b", (0.6, -0.25, 0.9), (down, 0, 0))
    return robot


def _tips(robot, values):
    """World positions of the three tips' far ends with the motors at ``values``."""
    for motor in robot.get_motors():
        motor.set_angle(values.get(motor.id, motor.default))
    tree = structure_of(robot)
    return {link.part: np.array(pose[0]) for link, pose in
            zip(tree.links, tree.link_poses({m.id: m.angle for m in robot.get_motors()}))
            if link.part and link.part.endswith("t")}


def test_a_gripper_nobody_tabled_closes_its_three_digits_towards_each_other(scene):
    robot = _gripper(scene)
    found = robot.get_grip_map()
    digits = {d["tip"]: d for d in found["digits"]}
    assert set(digits) == {"tt", "at", "bt"}
    assert [d["tip"] for d in found["digits"] if d["opposes"]] == ["tt"]  # alone on its side
    for tip, digit in digits.items():
        assert [m["motor"] for m in digit["motors"]] == [f"{tip[0]}1", f"{tip[0]}2"]
    assert found["approach"] == pytest.approx([0, -1, 0], abs=0.02)  # it grasps below itself
    opened = {m["motor"]: m["open"] for d in found["digits"] for m in d["motors"]}
    closed = {m["motor"]: m["closed"] for d in found["digits"] for m in d["motors"]}
    spread = lambda tips: max(np.linalg.norm(a - b) for a in tips.values() for b in tips.values())
    assert spread(_tips(robot, closed)) < 0.5 * spread(_tips(robot, opened))


def test_two_sliding_jaws_close_towards_each_other(scene):
    robot, palm = Robot(scene, "g"), Box(scene, "palm", 3, 0.5, 1)
    robot.attach_chain(palm)
    for name, x in (("l", -1.0), ("r", 1.0)):
        slot = palm.add_slot((x, -0.25, 0))
        jaw = Slider(scene, name, "x", -0.9, 0.9, 0)
        robot.add_chain(slot, jaw, Box(scene, f"{name}j", 0.2, 1.5, 0.6))
    found = robot.get_grip_map()
    closing = {d["tip"]: d["motors"][0] for d in found["digits"]}
    assert closing["lj"]["closed"] == pytest.approx(0.9) and closing["rj"]["closed"] == pytest.approx(-0.9)
    assert closing["lj"]["open"] == pytest.approx(-0.9) and closing["rj"]["open"] == pytest.approx(0.9)
    assert found["approach"] == pytest.approx([0, -1, 0], abs=0.02)


def test_link_poses_put_every_part_where_the_scene_does(scene):
    hand = EdgedHand(scene, "h", True)
    for i, motor in enumerate(hand.get_motors()):
        motor.set_angle(-0.1 * (i % 7))
    tree = structure_of(hand)
    poses = tree.link_poses({m.id: m.angle for m in hand.get_motors()})
    base = hand.world_pose()
    from server.core.kit.math3d import compose
    for link, pose in zip(tree.links, poses):
        if link.part is not None:
            placed = compose(base, compose(pose, link.shape))
            assert placed[0] == pytest.approx(scene.nodes[link.part].world_pose()[0], abs=1e-9)
