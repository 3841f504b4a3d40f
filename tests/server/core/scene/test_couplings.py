"""Coupled motors on their own: each leader's turn brings its followers' after it (theirs
after them), a follower's own turn is dropped, and a scene without couplings passes its
turns through untouched."""

import pytest

from server.core.model.motor import MotorZ
from server.core.model.robot import Robot


def _chain(scene, count):
    robot = Robot(scene, "r")
    motors = [MotorZ(scene, f"m{k}", -1.5, 1.5) for k in range(count)]
    robot.attach_chain(*motors)
    return motors


def test_without_couplings_the_turns_pass_through_as_they_are(scene):
    first, second = _chain(scene, 2)
    turns = [(first, 0.3), (second, -0.2)]
    assert scene.couplings.expand(turns, scene.tree_version) is turns


def test_a_leaders_turn_brings_its_followers_and_theirs_after_it(scene):
    leader, follower, last = _chain(scene, 3)
    follower.follow(leader, 0.5, 0.1)
    last.follow(follower, 2.0)
    turns = scene.couplings.expand([(leader, 0.4)], scene.tree_version)
    assert [(motor.id, angle) for motor, angle in turns] == [
        ("m0", 0.4), ("m1", pytest.approx(0.3)), ("m2", pytest.approx(0.6))]
    assert scene.couplings.expand([(follower, 1.0)], scene.tree_version) == []  # it only follows


def test_a_followers_share_stays_within_its_limits_and_a_freed_follower_turns_alone(scene):
    leader, follower = _chain(scene, 2)
    follower.follow(leader, 10.0)
    [_, (_, aim)] = scene.couplings.expand([(leader, 1.0)], scene.tree_version)
    assert aim == follower.max == 1.5
    follower.follow()  # freed: the index is worked out again
    assert scene.couplings.count == 0
    turns = [(follower, 0.2)]
    assert scene.couplings.expand(turns, scene.tree_version) is turns
