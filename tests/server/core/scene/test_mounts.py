"""Mounts: a dynamic robot is held where its script put it, from the moment it is built,
whether it was built in that world or moved into it."""

import pytest

from server.core.model.hands import EdgedHand
from server.core.model.motor import MotorZ
from server.core.model.parts import EdgedFinger
from server.core.model.robot import Robot
from server.core.scene.mounts import mount_of
from server.core.scene.scene import Scene


def _held_hand(put_again: bool) -> list[tuple]:
    """A hand in a dynamic world closing its fingers, its wrist put where it is every
    tick or never; every part's pose after every tick."""
    scene = Scene("wrist")
    hand = EdgedHand(scene, "h", True)
    hand.set_position((0, 3, 0))
    hand.set_rotation(0.3, 0, 0)
    scene.set_physics("dynamic")
    poses = []
    for k in range(30):
        hand.flex_fingers(0.04 * k)
        if put_again:
            hand.set_position((0, 3, 0))
        scene.tick(1 / 60)
        poses.append(tuple((node.id, node.position, node.quaternion) for node in scene.in_order_made()))
    scene.close()
    return poses


def test_a_wrist_put_where_it_is_every_tick_holds_as_one_never_put_again():
    # the mount holds a robot where a script put it, from the moment it is built: it took
    # the node's turn at the first setPosition, which by then was the physics' (the hand
    # turned a hair under its weight), and the two scripts' hands went apart
    assert _held_hand(put_again=True) == _held_hand(put_again=False)


def _switched_hand(built_first: bool) -> list[float]:
    """A hand made in a kinematic scene (built there at a tick, or not yet) before its
    script pauses it and makes it dynamic, then swept along, closing; its angles after."""
    scene = Scene("switch")
    hand = EdgedHand(scene, "h", False)
    hand.set_position((0, 1.2, 0))
    if built_first:
        scene.tick(1 / 60)
    scene.clock.pause("c1")
    scene.set_physics("dynamic")
    for tick in range(60):
        hand.flex_fingers(0.02 * tick)
        hand.set_position((0.01 * tick, 1.2, 0))
        scene.tick(1 / 60)
    angles = [motor.angle for motor in hand.get_motors()]
    scene.close()
    return angles


def test_a_robot_moved_into_a_dynamic_world_is_held_as_one_built_there():
    # one built in the kinematic world first was moved into the dynamic one without a
    # mount of its own: its first setPosition took the turn the physics had given it by
    # then, and whether a kinematic tick came before the script's setPhysics (a busy
    # server) decided which way its fingers went
    assert _switched_hand(built_first=True) == _switched_hand(built_first=False)


def test_a_robot_is_mounted_where_its_script_put_it_and_the_rest_where_they_are(scene):
    robot, motor, finger = Robot(scene, "r"), MotorZ(scene, "m"), EdgedFinger(scene, "f")
    robot.attach_chain(motor, finger)
    robot.set_position((0, 2, 0))
    assert mount_of(scene.bodies.physics, robot) is None  # kinematic mode: no mount
    scene.set_physics("dynamic")
    scene.tick(1 / 60)
    (position, _) = mount_of(scene.bodies.physics, robot)
    assert position == pytest.approx((0, 2, 0))
    assert mount_of(scene.bodies.physics, finger) is None  # not a robot
    robot.set_position((1, 2, 0))  # put elsewhere: its mount goes there
    scene.tick(1 / 60)
    assert mount_of(scene.bodies.physics, robot)[0] == pytest.approx((1, 2, 0))
