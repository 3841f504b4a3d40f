"""The scene's bodies: collision bodies and ray shapes kept where the tree puts the parts."""

import math

import numpy as np
import pytest

from server.core.kit import math3d
from server.core.model.hands import EdgedHand
from server.core.model.motor import MotorZ
from server.core.model.parts import Box, EdgedFinger
from server.core.model.robot import Robot
from server.core.scene.scene import Scene


def test_collision_bodies_follow_the_motors(scene):
    robot = Robot(scene, "r")
    finger = EdgedFinger(scene, "f", 1)
    motor = MotorZ(scene, "m")
    robot.attach_chain(motor, finger)
    robot.set_position((0, 1, 0))
    motor.set_angle(math.pi / 2)
    scene.tick(0.1)
    position, orientation = scene.bodies.physics.parts.pose("f")
    assert position == pytest.approx((0, 1, 0), abs=1e-6)
    assert orientation == pytest.approx(math3d.axis_angle("z", math.pi / 2), abs=1e-6)


def test_a_ray_hits_the_finger_where_the_tree_puts_it(scene):
    robot = Robot(scene, "r")
    motor = MotorZ(scene, "m")
    robot.attach_chain(motor, EdgedFinger(scene, "f", 1, 0.3, 0.3))
    robot.set_position((0, 1, 0))
    motor.set_angle(math.pi / 2)  # the finger now lies along -X at height 1
    scene.tick(0.1)
    # straight down at x = -0.5: the finger's upper face is 0.15 above its axis
    [(key, distance)] = scene.bodies.rays.first_hits((-0.5, 3, 0), (0, -1, 0), [0], 10)
    assert key == "f" and distance == pytest.approx(3 - 1.15, abs=1e-12)
    [(key, distance)] = scene.bodies.rays.first_hits((0.5, 3, 0), (0, -1, 0), [0], 10)
    assert key == "ground" and distance == 3


def test_a_hand_moved_as_a_whole_keeps_every_body_on_its_part(scene):
    hand = EdgedHand(scene, "h", True)
    scene.tick(0.1)
    hand.set_position((3, 1, -2))
    hand.flex_fingers(0.7)
    scene.tick(0.1)
    parts = [p for p in hand.get_parts() if p.physical]
    assert len(parts) == 16 and len(scene.bodies) == 16
    for part in parts:
        position, orientation = scene.bodies.physics.parts.pose(part.id)
        assert position == pytest.approx(part.world_pose()[0], abs=1e-12)
        same_turn = abs(sum(a * b for a, b in zip(orientation, part.world_pose()[1])))
        assert same_turn == pytest.approx(1, abs=1e-9)  # q and -q are one rotation
    for part in parts:  # straight down onto the middle of each part's box: the hand
        low, high = scene.bodies.physics.parts.aabb(part.id)
        x, z = (low[0] + high[0]) / 2, (low[2] + high[2]) / 2
        [(key, _)] = scene.bodies.rays.first_hits((x, 9, z), (0, -1, 0), [0], 20)
        assert key in {p.id for p in parts}, part.id


def test_a_tree_whose_joints_cannot_be_set_is_left_out_and_the_rest_turn(scene, monkeypatch):
    """A tick sets every turned tree's joints in one go; a tree that fails (a bug) is
    found one by one, left out, and the others still turn."""
    robots, fingers = [], []
    for i in range(3):
        robot, motor, finger = Robot(scene, f"r{i}"), MotorZ(scene, f"m{i}"), EdgedFinger(scene, f"f{i}", 1)
        robot.attach_chain(motor, finger)
        robot.set_position((3 * i, 1, 0))
        robots.append(robot)
        fingers.append(finger)
    scene.tick(0.1)
    turn = scene.bodies.physics.turn

    def failing(root, angles):
        if root == "r1":
            raise ValueError("a bug in one tree")
        turn(root, angles)
    monkeypatch.setattr(scene.bodies.physics, "turn", failing)
    for i in range(3):
        scene.get(f"m{i}").set_angle(math.pi / 2)
    scene.tick(0.1)
    assert scene.bodies.failures == 1 and "f1" not in scene.bodies.physics
    for i in (0, 2):
        assert scene.bodies.physics.parts.pose(f"f{i}")[1] == pytest.approx(
            math3d.axis_angle("z", math.pi / 2), abs=1e-6)


def test_a_part_that_cannot_be_placed_is_left_out_and_the_rest_move(scene, monkeypatch):
    boxes = [Box(scene, f"b{i}", 0.5, 0.5, 0.5) for i in range(3)]
    for i, box in enumerate(boxes):
        box.set_position((2 * i, 2, 0))
    scene.tick(0.1)
    for i, box in enumerate(boxes):
        box.set_position((2 * i, 0.2, 0))  # down onto the ground
    monkeypatch.setattr(boxes[1], "local_pose", lambda: math.sqrt(-1))  # a bug in one part
    frame = scene.tick(0.1)[-1]
    assert scene.bodies.failures == 1 and "b1" not in scene.bodies.physics
    assert frame["contacts"]["begin"] == [["b0", "ground"], ["b2", "ground"]]


def test_a_part_scaled_gets_a_shape_of_its_new_size(scene):
    box = Box(scene, "b", 1, 1, 1)
    box.set_position((0, 2, 0))
    scene.tick(0.1)
    [(_, before)] = scene.bodies.rays.first_hits((0, 5, 0), (0, -1, 0), [0], 10)
    assert "ground" not in scene.bodies.touching(box)
    box.set_scale((1, 4, 1))  # from y = 0 to y = 4
    scene.tick(0.1)
    [(key, after)] = scene.bodies.rays.first_hits((0, 5, 0), (0, -1, 0), [0], 10)
    assert (before, key, after) == (pytest.approx(2.5), "b", pytest.approx(1))
    assert "ground" in scene.bodies.touching(box)


def test_a_sensor_on_a_part_is_placed_from_the_parts_pose_in_bullet(scene):
    from server.core.model.sensor import Sensor
    hand = EdgedHand(scene, "h", True)
    hand.set_position((1, 2, 3))
    tip = next(p for p in hand.get_parts() if p.type_name == "EdgedTip")
    on_tip = Sensor(scene, "s")
    on_tip.attach_to_slot(tip)
    on_tip.set_rotation(0.3, 0, 0)
    scene.tick(0.1)
    hand.flex_fingers(0.6)
    scene.bodies.sync()
    positions, turns = scene.bodies.world_frames([on_tip, tip, hand])
    for k, node in enumerate((on_tip, tip, hand)):
        position, quat = node.world_pose()
        assert positions[k].tolist() == pytest.approx(position, abs=1e-12)
        assert turns[k].ravel().tolist() == pytest.approx(np.ravel(math3d.to_matrix(quat)).tolist(), abs=1e-12)
    on_tip.set_position((0.1, 0, 0))  # its offset from the tip is worked out again
    on_tip.set_rotation(0.5, 0.2, 0)
    hand.spread_fingers(0.2)
    scene.bodies.sync()
    positions, turns = scene.bodies.world_frames([on_tip])
    want_p, want_q = on_tip.world_pose()
    assert positions[0].tolist() == pytest.approx(want_p, abs=1e-12)
    assert turns[0].ravel().tolist() == pytest.approx(np.ravel(math3d.to_matrix(want_q)).tolist(), abs=1e-12)
    tip.set_scale((1, 2, 1))  # a stretched part: the tree composes the whole way
    scene.bodies.sync()
    [position] = scene.bodies.world_frames([on_tip])[0].tolist()
    assert position == pytest.approx(on_tip.world_pose()[0], abs=1e-12)


_SAME_WORLD = """
import math
from server.core.scene.scene import Scene
from server.core.model.hands import EdgedHand
from server.core.model.parts import Ball, Box
scene = Scene("same")
hand = EdgedHand(scene, "hand", True)
hand.set_rotation(-math.pi / 2, 0, 0)
hand.set_position((0, 2.2, 0))
for k in range(6):  # made in one tick: built together
    Ball(scene, f"ball{k}", 0.3).set_position((0.4 * k - 1, 1.5 + 0.7 * k, -1.6))
Box(scene, "table", 4, 1, 4).set_position((0, 0.5, -1.5))
scene.get("table").set_static(True)
scene.set_physics("dynamic")
for step in range(90):
    hand.flex_fingers(min(1.2, step / 40))
    scene.tick(1 / 60)
print([scene.get(f"ball{k}").position for k in range(6)], hand.get_angles())
"""


def test_the_same_script_makes_the_same_dynamic_world_whatever_python_hashes(tmp_path):
    """Bullet's solver visits bodies in the order they were added, so they are added in
    the order they were made, not in a set's order (which changes with Python's hash seed
    from one server run to the next): a task's seed gives the same results every run."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[4]
    worlds = [subprocess.run([sys.executable, "-c", _SAME_WORLD], cwd=root, check=True,
                             capture_output=True, text=True,
                             env={**os.environ, "PYTHONHASHSEED": seed}).stdout
              for seed in ("1", "2", "3")]
    assert worlds[0] and worlds[0] == worlds[1] == worlds[2]


def test_a_lone_part_attached_to_a_robot_leaves_no_body_where_it_was(scene):
    robot = Robot(scene, "r")
    robot.attach_chain(MotorZ(scene, "m"), EdgedFinger(scene, "f", 1))
    lone = EdgedFinger(scene, "lone", 1)
    lone.set_position((5, 0, 0))  # lying on the ground, away from the robot
    scene.tick(0.1)
    assert sorted(scene.bodies.physics.roots()) == ["lone", "r"]
    lone.attach_to_slot(scene.get("f"))
    scene.tick(0.1)
    assert scene.bodies.physics.roots() == ["r"]  # its own tree went: no ghost left behind
    assert "ground" not in scene.bodies.touching(lone)
    scene.get("m").set_angle(0.3)
    robot.set_position((0, 3, 0))
    scene.tick(0.1)
    assert scene.failures == 0 and scene.bodies.failures == 0


def _finger_robot(scene):
    robot = Robot(scene, "r")
    motor, finger = MotorZ(scene, "m"), EdgedFinger(scene, "f", 1)
    robot.attach_chain(motor, finger)
    robot.set_position((0, 2, 0))
    motor.set_angle(0.4)
    return motor, finger


def test_trees_made_before_a_physics_switch_are_built_once_in_the_new_world(scene):
    """An import (every restoreState) makes every tree anew and then switches the physics:
    they are built in the new world only, where they are and as their motors are turned,
    as a tree built before the switch is moved."""
    motor, finger = _finger_robot(scene)
    built: list[str] = []
    physics = scene.bodies.physics
    add_tree = physics.add_tree
    physics.add_tree = lambda tree, *args: built.append(tree.root) or add_tree(tree, *args)
    scene.set_physics("dynamic")
    assert built == ["r"] and scene.bodies.physics.dynamics is not None
    assert motor.get_angle() == pytest.approx(0.4)
    other = Scene("built-before")
    _, moved = _finger_robot(other)
    other.tick(0.1)  # built in the kinematic world
    other.set_physics("dynamic")
    assert scene.bodies.physics.parts.pose(finger.id) == other.bodies.physics.parts.pose(moved.id)
    other.close()


def test_a_still_world_is_not_measured_again_and_a_move_is(scene):
    """Contacts are measured when something was built, put or moved, not every tick: a
    still scene of 100 hands spent most of a core finding the same contacts again."""
    robot, motor, finger = Robot(scene, "r"), MotorZ(scene, "m"), EdgedFinger(scene, "f")
    robot.attach_chain(motor, finger)
    robot.set_position((0, 1, 0))
    box = Box(scene, "b", 1, 0.1, 0.1)
    box.set_position((0, 1.5, 0))
    for _ in range(3):  # (new bodies start in the crowd, and leave it once measured)
        scene.tick(1 / 60)
    tracker = scene.bodies.tracker
    updates = tracker.updates
    assert scene.snapshot()["contacts"] == [["b", "f"]]
    for _ in range(5):
        scene.tick(1 / 60)
    assert tracker.updates == updates and scene.snapshot()["contacts"] == [["b", "f"]]
    motor.set_angle(0.1)  # a turn: measured on the next tick
    scene.tick(1 / 60)
    assert tracker.updates == updates + 1
    box.set_position((5, 1.5, 0))  # away from the finger
    ticked = scene.tick(1 / 60)
    assert next(m for m in ticked if m["op"] == "frame")["contacts"] == {"begin": [], "end": [["b", "f"]]}
    assert scene.snapshot()["contacts"] == []
