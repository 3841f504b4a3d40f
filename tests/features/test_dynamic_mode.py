"""Dynamic mode in a scene: things fall and rest, slide off slopes, motors stop at what is in
their way, mounts drag hands smoothly, forces are sensed; kinematic mode as before."""

import math

import pytest

from server.core.model.hands import AnthroHand, EdgedHand, RoundHand
from server.core.model.motor import MotorZ
from server.core.model.parts import Ball, Box, EdgedFinger, EdgedPalm
from server.core.model.robot import Robot
from server.core.model.sensor import Sensor

TICK = 1 / 60


def run(scene, seconds):
    frames = []
    for _ in range(round(seconds / TICK)):
        frames.append(scene.tick(TICK)[-1])
    return frames


def test_a_ball_dropped_from_2_m_lands_and_rests_without_jitter(scene):
    ball = Ball(scene, "b", 0.25)
    ball.set_position((0, 2, 0))
    scene.set_physics("dynamic")
    heights = [frame["poses"]["b"][1] for frame in run(scene, 1) if "b" in frame.get("poses", {})]
    assert heights[0] < 2 and min(heights) > 0.24  # it fell, and never through the ground
    run(scene, 1)
    resting = [ball.position[1] for _ in range(60) if not run(scene, TICK) or True]
    assert max(resting) - min(resting) < 0.001 and ball.position[1] == pytest.approx(0.25, abs=0.002)


def test_a_box_on_a_tilted_palm_slides_off(scene):
    robot = Robot(scene, "r")
    EdgedPalm(scene, "p").attach_to_slot(robot)
    robot.set_position((0, 2, 0))
    robot.set_rotation(-math.pi / 2 + 0.5, 0, 0)  # palm up, tilted half a radian
    box = Box(scene, "b", 0.3, 0.3, 0.3)
    box.set_position((0, 2.6, -0.7))
    scene.set_physics("dynamic", {"friction": 0.3})  # below tan(0.5): it must slide
    run(scene, 3)
    assert box.position[1] < 0.3 and box.position[2] > 0.5  # down the slope, on the ground


def test_a_fist_closing_on_a_fixed_box_stops_at_the_box(scene):
    hand = EdgedHand(scene, "h", True)
    hand.set_position((0, 4, 0))
    hand.set_rotation(-math.pi / 2, 0, 0)  # palm down, fingers along -Z
    hand.flex_fingers(0)
    Box(scene, "fixed", 1.2, 0.6, 1.2).set_position((0.3, 3.5, -2.2))
    scene.get("fixed").set_static(True)
    scene.set_physics("dynamic")
    run(scene, 0.5)
    hand.flex_fingers(1.5)
    run(scene, 2)
    index, middle = hand.get_angles()[5:8], hand.get_angles()[9:12]
    assert all(m.target == -1.5 for m in hand.get_motors()[5:8])
    assert index[0] > -1.0 and middle[0] > -1.0  # stopped by the box, far from their targets
    assert hand.get_angles()[1] == pytest.approx(-1.5, abs=0.05)  # the thumb meets nothing
    assert scene.get("fixed").position == (0.3, 3.5, -2.2)


@pytest.mark.parametrize("kind", [EdgedHand, RoundHand, AnthroHand])
def test_a_mounted_hand_follows_its_mount_smoothly_and_keeps_its_pose(scene, kind):
    hand = kind(scene, "h", True)
    hand.set_position((0, 3, 0))
    scene.set_physics("dynamic")
    run(scene, 0.5)
    assert hand.position == pytest.approx((0, 3, 0), abs=1e-3)  # held against gravity
    hand.set_position((0, 5, 0))
    heights = [hand.position[1] for _ in range(30) if run(scene, TICK) is not None]
    assert heights[0] < 5 and heights[-1] == pytest.approx(5, abs=0.01)
    assert all(b - a < 0.5 for a, b in zip(heights, heights[1:]))  # no jump: dragged there


def test_a_heavy_hand_under_strong_gravity_does_not_sink_at_its_mount(scene):
    hand = AnthroHand(scene, "h", True)
    hand.set_position((0, 3, 0))
    scene.set_physics("dynamic", {"gravity": 160, "density": 5000})
    run(scene, 1)
    assert hand.position == pytest.approx((0, 3, 0), abs=2e-3)


def test_the_clock_of_a_dynamic_scene_is_its_physics_a_late_tick_slows_it(scene):
    ball = Ball(scene, "b", 0.25)
    ball.set_position((0, 50, 0))
    scene.set_physics("dynamic")
    scene.tick(1.0)  # a tick a whole second late: the world catches up at most 2 ticks
    assert scene.time == pytest.approx(2 / 60)
    fallen = 50 - ball.position[1]
    assert fallen == pytest.approx(9.81 * scene.time ** 2 / 2, rel=0.1)  # falls as its clock says


def test_masses_come_from_volume_and_density_unless_given(scene):
    box = Box(scene, "b", 1, 2, 0.5)
    assert box.get_mass() == pytest.approx(1000.0)
    scene.set_physics("dynamic", {"density": 500})
    assert box.get_mass() == pytest.approx(500.0)
    box.set_mass(3.0)
    assert box.get_mass() == 3.0


def test_a_sensor_feels_what_presses_on_its_part(scene):
    pad = Box(scene, "pad", 2, 0.2, 2)
    pad.set_static(True)
    sensor = Sensor(scene, "s")
    sensor.attach_to_slot(pad)
    load = Box(scene, "load", 0.5, 0.5, 0.5)
    load.set_position((0, 0.5, 0))
    load.set_mass(10.0)
    pad.set_position((0, 0.1, 0))
    assert sensor.sense_force() == 0.0  # kinematic mode: nothing pushes
    scene.set_physics("dynamic")
    frames = run(scene, 1.5)
    assert sensor.sense_force() == pytest.approx(10 * 9.81, rel=0.05)
    assert frames[-1].get("forces", {}).get("load") or \
        any(frame.get("forces", {}).get("load") for frame in frames)


def test_motors_drive_with_at_most_their_torque(scene):
    robot = Robot(scene, "r")
    motor = MotorZ(scene, "m")
    arm = EdgedFinger(scene, "f", 2.0)
    robot.attach_chain(motor, arm)
    robot.set_position((0, 3, 0))
    motor.set_angle(-math.pi / 2)  # the arm sticks out sideways: gravity pulls it down
    weak = motor.set_max_torque(10.0)
    assert weak is motor and motor.get_max_torque() == 10.0
    scene.set_physics("dynamic")
    run(scene, 1.5)
    assert motor.angle < -math.pi / 2 - 0.5 or motor.angle > 0.5 - math.pi / 2  # it sagged
    motor.set_max_torque(1e5)
    motor.set_angle(-math.pi / 2)
    run(scene, 1.5)
    assert motor.angle == pytest.approx(-math.pi / 2, abs=0.02)  # strong enough to hold it


def test_back_to_kinematic_things_stay_where_the_physics_left_them(scene):
    ball = Ball(scene, "b", 0.5)
    ball.set_position((0, 3, 0))
    scene.set_physics("dynamic")
    run(scene, 2)
    scene.set_physics("kinematic")
    run(scene, 0.5)
    assert ball.position[1] == pytest.approx(0.5, abs=0.01)
    ball.set_position((0, 3, 0))
    run(scene, 0.5)
    assert ball.position == (0, 3, 0)  # nothing falls in kinematic mode
