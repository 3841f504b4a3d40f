"""Actions: [-1, 1] per motor, over each motor's limits (or its way in the grip map), or
a share of its torque bound."""

from __future__ import annotations

import math

import numpy as np

import virtual_prosthetics as vp
from virtual_prosthetics.gym.actions import ActionMap, action_map
from virtual_prosthetics.tasks.grip import hand_grip
from virtual_prosthetics.tasks.observation import Angles, Torques


def test_an_action_spans_each_motors_range_and_comes_back_from_its_angles():
    actions = ActionMap("angles", ((-1.0, 1.0), (0.0, 2.0)), (0.5, 0.5))
    assert actions.space().shape == (2,) and actions.space().contains(np.zeros(2, np.float32))
    assert actions.targets(np.array([-1.0, 1.0])) == Angles([-1.0, 2.0])
    assert actions.targets(np.array([5.0, -7.0])) == Angles([1.0, 0.0])  # clipped to [-1, 1]
    assert np.allclose(actions.action_of([0.5, 0.5]), [0.5, -0.5])


def test_torque_actions_are_shares_of_each_motors_bound():
    actions = ActionMap("torques", ((-1.0, 1.0), (-1.0, 1.0)), (0.3, 1.2))
    assert actions.targets(np.array([1.0, -0.5])) == Torques([0.3, -0.6])


def test_a_hands_motors_without_limits_take_their_way_in_the_grip_map(scene):
    robot = vp.Robot()
    palm = vp.Box(2, 0.4, 2)
    robot.attach_chain(palm)
    limited = vp.MotorX(-0.5, 1.0, 0)
    free = vp.MotorX()  # no limits: its way closed in the grip map, or a quarter turn
    limited.attach_to_slot(palm, palm.add_slot(0, -0.2, 0))
    robot.add_chain(limited, vp.EdgedFinger(0.7), free, vp.EdgedTip())
    scene.sync()
    grip = hand_grip(robot)
    made = action_map(robot, grip, "angles")
    assert made.ranges[0] == (-0.5, 1.0)
    low, high = made.ranges[1]
    assert math.isfinite(low) and math.isfinite(high) and high > low
    assert made.torques == (limited.get_max_torque(), free.get_max_torque())
