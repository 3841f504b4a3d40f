"""Robots: chains, motor order, angles and positions."""

import math

import pytest

from server.core.model.motor import MotorX, MotorZ
from server.core.model.parts import Box, EdgedFinger
from server.core.model.robot import Robot


def chain(scene, prefix="r"):
    robot = Robot(scene, prefix)
    parts = [MotorZ(scene, f"{prefix}.m1"), EdgedFinger(scene, f"{prefix}.f1", 1),
             MotorZ(scene, f"{prefix}.m2"), EdgedFinger(scene, f"{prefix}.f2", 1)]
    assert robot.attach_chain(*parts) is parts[-1]
    return robot, parts


@pytest.mark.parametrize("angles,end", [
    ((0, 0), (0, 2, 0)),
    ((math.pi / 2, 0), (-2, 0, 0)),       # +Y turned a quarter about Z points to -X
    ((0, -math.pi / 2), (1, 1, 0)),       # second joint bends the top finger to +X
    ((math.pi / 2, -math.pi / 2), (-1, 1, 0)),
])
def test_chain_slot_world_positions_at_known_angles(scene, angles, end):
    robot, parts = chain(scene)
    robot.set_position((0.5, 0, -1))
    robot.set_angles(*angles)
    tip = parts[-1].slots[0].world_pose()[0]
    assert tip == pytest.approx((end[0] + 0.5, end[1], end[2] - 1), abs=1e-12)


def test_motor_order_is_depth_first_and_follows_later_attachments(scene):
    robot, parts = chain(scene)
    assert [m.id for m in robot.get_motors()] == ["r.m1", "r.m2"]
    side = MotorX(scene, "side")
    side.attach_to_slot(parts[1])  # on the first finger's slot, after m2 was attached
    assert [m.id for m in robot.get_motors()] == ["r.m1", "r.m2", "side"]
    late = MotorX(scene, "late")
    late.attach_to_slot(parts[0])
    assert [m.id for m in robot.get_motors()] == ["r.m1", "r.m2", "side", "late"]
    assert [p.id for p in robot.get_parts()] == ["r.m1", "r.f1", "r.m2", "r.f2", "side", "late"]


def test_add_chain_can_start_anywhere(scene):
    robot = Robot(scene, "r")
    box, finger = Box(scene, "b"), EdgedFinger(scene, "f")
    assert robot.add_chain(robot, box, finger) is finger
    assert finger.parent is box and box.parent is robot


def test_angles_by_index(scene):
    robot, _ = chain(scene)
    robot.set_angle(1, 0.25)
    robot.set_angle(7, 1.0)  # no such motor: ignored
    robot.set_angle(0, None)
    assert robot.get_angles() == [0, 0.25]
    assert robot.get_angle(1) == 0.25 and robot.get_angle(9) == 0
    robot.set_angles(None, 0.5, 99)  # None keeps, extras ignored
    assert robot.get_angles() == [0, 0.5]


def test_set_position_without_arguments_takes_robot_out_of_the_scene(scene):
    robot, _ = chain(scene)
    scene.tick(0.01)
    assert len(scene.bodies.physics) == 2 and "r.f1" in scene.bodies.physics and "r.f2" in scene.bodies.physics
    robot.set_position()
    scene.tick(0.01)
    assert len(scene.bodies.physics) == 0 and "r" in scene.nodes
    robot.set_position((0, 1, 0))
    scene.tick(0.01)
    assert len(scene.bodies.physics) == 2 and robot.get_position() == (0, 1, 0)


def test_set_rotation_turns_the_whole_robot(scene):
    robot, parts = chain(scene)
    robot.set_rotation(0, 0, math.pi / 2, "ZYX")
    assert parts[-1].slots[0].world_pose()[0] == pytest.approx((-2, 0, 0))


def test_a_robot_lists_its_motors_in_index_order_and_says_when_that_changes(scene):
    robot, first, second = Robot(scene, "r"), MotorZ(scene, "m1"), MotorX(scene, "m2")
    finger = EdgedFinger(scene, "f")
    assert robot.describe()["motors"] == []
    with scene.recording() as changes:
        robot.attach_chain(first, finger)
        second.attach_to_slot(finger)
    assert robot.describe()["motors"] == ["m1", "m2"] == [m.id for m in robot.get_motors()]
    assert "motors" in changes.updates["r"]
    delta = scene.delta(changes)
    assert delta["updates"]["r"]["motors"] == ["m1", "m2"]
    with scene.recording() as changes:
        Box(scene, "b").attach_to_slot(finger, 3)  # no motor moved: the order stands
    assert "motors" not in changes.updates.get("r", set())
    with scene.recording() as changes:
        scene.delete(second)
    assert scene.delta(changes)["updates"]["r"]["motors"] == ["m1"]
