"""Trees compiled into articulations: links carry parts, motors are joints, and Bullet's
forward kinematics puts every part where the tree does."""

import math

import pytest

from server.core.model.hands import AnthroHand, EdgedHand, RoundHand
from server.core.model.motor import Motor, MotorX, MotorY, MotorZ
from server.core.model.parts import Box, EdgedFinger, EdgedTip
from server.core.model.robot import Robot
from server.core.model.sensor import Sensor
from server.core.model.structure import base_pose, structure_of
from server.core.physics.engine import PhysicsWorld


@pytest.fixture
def world():
    w = PhysicsWorld()
    yield w
    w.close()


def same_pose(a, b, tolerance=1e-12):
    (pa, qa), (pb, qb) = a, b
    turn = abs(sum(x * y for x, y in zip(qa, qb)))  # q and -q are one rotation
    return max(abs(x - y) for x, y in zip(pa, pb)) <= tolerance and abs(turn - 1) <= tolerance


@pytest.mark.parametrize("kind, links, joints, parts", [(EdgedHand, 21, 20, 16),
                                                         (RoundHand, 21, 20, 16),
                                                         (AnthroHand, 23, 22, 17)])
@pytest.mark.parametrize("left", [True, False])
def test_every_part_of_every_hand_is_where_the_tree_puts_it(scene, world, kind, links, joints,
                                                             parts, left):
    hand = kind(scene, "h", left)
    hand.set_position((1, 2, -0.5))
    hand.set_rotation(0.3, -0.2, 0.1)
    hand.flex_fingers(0.4)
    hand.spread_fingers(0.3)
    tree = structure_of(hand)
    assert (len(tree.links), len(tree.joints()), len(tree.parts())) == (links, joints, parts)
    world.add_tree(tree, base_pose(hand), {m.id: m.angle for m in hand.get_motors()})
    for key, pose in zip(*world.part_poses("h")):
        assert same_pose(pose, scene.nodes[key].world_pose()), key


def test_a_joint_rides_on_the_part_it_turns_and_two_joints_meeting_get_a_bare_link(scene):
    robot = Robot(scene, "r")
    spread, flex = MotorX(scene, "spread"), MotorZ(scene, "flex")
    robot.attach_chain(spread, flex, EdgedFinger(scene, "f"))
    tree = structure_of(robot)
    bare, finger = tree.links
    assert (bare.part, bare.joint.motor, bare.parent) == (None, "spread", -1)
    assert (finger.part, finger.joint.motor, finger.parent) == ("f", "flex", 0)


def test_a_motor_with_nothing_physical_below_it_makes_no_link(scene):
    robot = Robot(scene, "r")
    motor = MotorZ(scene, "m")
    robot.attach_chain(Box(scene, "b"), motor)
    Sensor(scene, "s").attach_to_slot(motor)
    tree = structure_of(robot)
    assert [link.part for link in tree.links] == ["b"] and tree.joints() == []


def test_a_flipped_motor_turns_about_its_axis_reversed(scene, world):
    robot = Robot(scene, "r")
    motor = MotorZ(scene, "m")
    robot.attach_chain(motor, EdgedFinger(scene, "f"))
    motor.flip(True)
    motor.set_angle(0.5)
    [link] = structure_of(robot).links
    assert link.joint.axis == (0.0, 0.0, -1.0)
    world.add_tree(structure_of(robot), base_pose(robot), {"m": 0.5})
    assert same_pose(world.part_poses("r")[1][0], scene.nodes["f"].world_pose())


def test_a_scaled_node_stretches_where_its_children_sit_and_their_shapes(scene, world):
    robot = Robot(scene, "r")
    motor = MotorZ(scene, "m")
    robot.attach_chain(Box(scene, "b", 1, 1, 1), motor, Box(scene, "top", 1, 1, 1))
    scene.nodes["b"].set_scale((1, 2, 1))
    motor.set_angle(math.pi / 3)
    tree = structure_of(robot)
    top = next(link for link in tree.links if link.part == "top")
    assert top.geometry["size"] == [1, 2, 1]
    world.add_tree(tree, base_pose(robot), {"m": motor.angle})
    for key, pose in zip(*world.part_poses("r")):
        assert same_pose(pose, scene.nodes[key].world_pose()), key


def test_a_lone_part_is_a_base_and_a_robot_out_of_the_scene_has_no_parts(scene):
    box = Box(scene, "b")
    tree = structure_of(box)
    assert (tree.base_part, tree.links) == ("b", ())
    robot = Robot(scene, "r")
    robot.attach_chain(MotorZ(scene, "m"), EdgedFinger(scene, "f"))
    robot.set_position()
    assert structure_of(robot).parts() == ()


def test_what_hangs_below_a_part_riding_on_a_joint_follows_the_part_not_the_joint(scene, world):
    # a Y motor's slot is on its top: the finger sits 0.1 above the joint, and the tip
    # (on its own joint) must be placed from the finger's frame, not from the joint's
    robot = Robot(scene, "r")
    robot.attach_chain(MotorZ(scene, "m0", math.pi / 2, -math.pi / 2, 0, 0.2, 0.3),
                       MotorY(scene, "m1", -1, 1, 0, 0.2, 0.1), EdgedFinger(scene, "f", 0.75),
                       MotorZ(scene, "m2", 0, -math.pi / 2, 0, 0.25, 0.08),
                       EdgedTip(scene, "tip", 0.75))
    robot.set_angles(-1.45, 0.3, -1.2)
    world.add_tree(structure_of(robot), base_pose(robot),
                   {m.id: m.angle for m in robot.get_motors()})
    for key, pose in zip(*world.part_poses("r")):
        assert same_pose(pose, scene.nodes[key].world_pose()), key


def test_a_motor_about_any_unit_axis_is_a_joint_about_it_where_the_tree_puts_its_part(scene, world):
    robot = Robot(scene, "r")
    axis = (0.0, 0.6, 0.8)
    motor = Motor(scene, "m", axis, -1, 1)
    robot.attach_chain(motor, EdgedFinger(scene, "f"))
    motor.set_angle(0.7)
    [link] = structure_of(robot).links
    assert link.joint.axis == axis
    world.add_tree(structure_of(robot), base_pose(robot), {"m": 0.7})
    assert same_pose(world.part_poses("r")[1][0], scene.nodes["f"].world_pose())
    motor.flip(True)
    assert structure_of(robot).links[0].joint.axis == (-0.0, -0.6, -0.8)
