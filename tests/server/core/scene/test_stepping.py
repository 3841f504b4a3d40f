"""Dynamic mode's steps: a world at rest stays so until something is driven, and followers
aim at their share of their leader's real angle (a finger whose first joint an object
stops stops curling, as a linkage does)."""

import math

import pytest

from server.core.model.motor import MotorZ
from server.core.model.parts import Box, EdgedFinger
from server.core.model.robot import Robot


def finger(scene):
    robot = Robot(scene, "r")
    motors = [MotorZ(scene, f"m{k}", -1.5, 1.5) for k in range(3)]
    segments = [EdgedFinger(scene, f"f{k}").set_mass(1.0) for k in range(3)]
    robot.attach_chain(motors[0], segments[0], motors[1], segments[1], motors[2], segments[2])
    robot.set_position((0.0, 3.0, 0.0))
    motors[1].follow(motors[0], 0.5, 0.1)
    motors[2].follow(motors[0], -1.0)
    return robot, motors


def settle(scene, ticks=180):
    for _ in range(ticks):
        scene.tick(1 / 60)


def test_followers_turn_with_their_leaders_real_angle(scene):
    robot, (a, b, c) = finger(scene)
    scene.set_physics("dynamic", {"gravity": 0.0})
    a.set_angle(-0.8)
    settle(scene)
    assert a.angle == pytest.approx(-0.8, abs=0.01)
    assert b.angle == pytest.approx(0.5 * a.angle + 0.1, abs=1e-3)  # geared to where it is
    assert c.angle == pytest.approx(-a.angle, abs=1e-3)


def test_a_leader_stopped_by_an_object_stops_its_followers(scene):
    robot, (a, b, c) = finger(scene)
    wall = Box(scene, "wall", 0.5, 3.0, 3.0)
    wall.set_static()
    wall.set_position((-0.9, 3.8, 0.0))  # in the way of the first segment turning left
    a.set_max_torque(50.0)  # N·m: a finger of metres and kilograms, its followers strong
    b.set_max_torque(2e4)
    c.set_max_torque(2e4)
    scene.set_physics("dynamic", {"gravity": 0.0, "unit": 1.0})
    a.set_angle(1.4)
    settle(scene)
    assert a.angle < 1.0  # the wall holds the first segment
    assert b.angle == pytest.approx(0.5 * a.angle + 0.1, abs=2e-3)  # and so its followers
    assert a.target == 1.4  # though it was sent further
    assert math.isfinite(c.angle) and c.angle == pytest.approx(-a.angle, abs=2e-3)


def test_a_world_at_rest_takes_no_steps_until_a_motor_is_driven(scene):
    robot, (a, b, c) = finger(scene)
    scene.set_physics("dynamic", {"gravity": 0.0})
    settle(scene)
    stepping = scene.bodies.stepping
    assert stepping.still
    rest = stepping.advance(1 / 60, exact=False)
    assert (rest.seconds, rest.angles, rest.poses, rest.moved, rest.stirred) == \
        (pytest.approx(1 / 60), {}, {}, [], False)
    a.set_angle(0.5)  # a new target: driven from the next step
    driven = stepping.advance(1 / 60, exact=False)
    assert driven.stirred and driven.moved == ["r"] and a.id in driven.angles
    assert not stepping.still
