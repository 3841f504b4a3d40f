"""Motor limits, clamping, flipping and naming as spec/parts.md says."""

import math

import pytest

from server.core.kit import math3d
from server.core.model.motor import Motor, MotorX, MotorY, MotorZ, Slider
from server.core.model.parts import Box
from server.core.model.robot import Robot
from server.core.physics.dynamics import DEFAULT_MAX_FORCE
from server.core.kit.errors import OutOfRange


def test_limits_are_swapped_and_default_clamped(scene):
    motor = MotorZ(scene, "m", math.pi / 4, -math.pi / 2, -3)
    assert (motor.min, motor.max) == (-math.pi / 2, math.pi / 4)
    assert motor.get_angle() == -math.pi / 2


def test_set_angle_clamps_and_ignores_none_and_nan(scene):
    motor = MotorX(scene, "m", -0.7, 0.7, 0)
    motor.set_angle(2)
    assert motor.get_angle() == 0.7
    motor.set_angle(None)
    motor.set_angle(math.nan)
    assert motor.get_angle() == 0.7
    motor.set_angle(-math.inf)
    assert motor.get_angle() == -0.7


def test_unbounded_motor_refuses_infinite_angle(scene):
    motor = Motor(scene, "m", "y")
    with pytest.raises(OutOfRange):
        motor.set_angle(math.inf)
    assert motor.get_angle() == 0


def test_flip_turns_the_other_way_but_reports_the_same_angle(scene):
    plain, flipped = MotorZ(scene, "a"), MotorZ(scene, "b")
    assert flipped.flip(True) is flipped
    for motor in (plain, flipped):
        motor.set_angle(0.5)
    assert flipped.get_angle() == plain.get_angle() == 0.5
    assert plain.world_pose()[1] == pytest.approx(math3d.axis_angle("z", 0.5))
    assert flipped.world_pose()[1] == pytest.approx(math3d.axis_angle("z", -0.5))
    flipped.flip(False)
    assert flipped.world_pose()[1] == pytest.approx(math3d.axis_angle("z", 0.5))


def test_set_name_returns_the_motor(scene):
    motor = MotorY(scene, "m")
    assert motor.set_name("Base rotor") is motor
    assert motor.name == "Base rotor"


@pytest.mark.parametrize("cls,axis,width,height,slot", [
    (MotorX, "x", 0.1, 0.05, (0, 0, 0)),
    (MotorY, "y", 0.3, 0.05, (0, 0.05, 0)),
    (MotorZ, "z", 0.1, 0.05, (0, 0, 0)),
])
def test_motor_defaults_and_slot_zero(scene, cls, axis, width, height, slot):
    motor = cls(scene, "m")
    assert (motor.axis, motor.width, motor.height) == (axis, width, height)
    assert motor.slots[0].position == pytest.approx(slot)
    assert (motor.min, motor.max, motor.angle) == (-math.inf, math.inf, 0)


def test_motor_y_slot_sits_on_top_of_a_custom_height(scene):
    motor = MotorY(scene, "m", 0, 1, 0, 0.25, 0.1)
    assert motor.slots[0].position == pytest.approx((0, 0.1, 0))
    assert motor.geometry()["radius"] == pytest.approx(0.125)


def test_motors_are_not_physical(scene):
    MotorZ(scene, "m")
    scene.tick(0.01)
    assert len(scene.bodies.physics) == 0


def coupled_finger(scene):
    """A robot with one finger of three motors."""
    from server.core.model.parts import EdgedFinger
    from server.core.model.robot import Robot
    robot = Robot(scene, "r")
    motors = [MotorZ(scene, f"m{k}", -1.5, 0) for k in range(3)]
    robot.attach_chain(motors[0], EdgedFinger(scene, "f0"), motors[1], EdgedFinger(scene, "f1"),
                       motors[2], EdgedFinger(scene, "f2"))
    return robot, motors


def test_a_follower_turns_with_its_leader_at_its_ratio_and_offset_within_its_limits(scene):
    robot, (a, b, c) = coupled_finger(scene)
    assert b.follow(a, 0.5, -0.1) is b
    c.follow(b, 2.0)
    assert (b.angle, c.angle) == (-0.1, -0.2)  # placed at once from the leader
    a.set_angle(-1.0)
    assert (a.angle, b.angle, c.angle) == (-1.0, -0.6, -1.2)
    a.set_angle(-1.5)
    assert (b.angle, c.angle) == (-0.85, -1.5)  # 2 × -0.85 clamped to c's limit
    b.set_angle(0.0)  # a follower moves only with its leader
    robot.set_angles(-0.2, -0.9, -0.9)
    assert robot.get_angles() == [-0.2, -0.2, -0.4]
    b.follow()  # freed, it turns by itself; c still follows it
    b.set_angle(-0.3)
    assert (a.angle, b.angle, c.angle) == (-0.2, -0.3, -0.6)


def test_a_motor_follows_only_a_motor_and_never_itself(scene):
    from server.core.kit.errors import Cycle, WrongType
    robot, (a, b, c) = coupled_finger(scene)
    b.follow(a)
    with pytest.raises(Cycle, match="m0 cannot follow m1: m1 turns with m0 already"):
        a.follow(b)
    with pytest.raises(Cycle):
        a.follow(a)
    with pytest.raises(WrongType, match="can only follow a motor; f0 is a EdgedFinger"):
        a.follow(scene.nodes["f0"])
    assert a.following is None  # refused calls changed nothing
    other = MotorZ(scene, "elsewhere")  # another robot's: a motor may drive any joint
    b.follow(other, -1.0)
    other.set_angle(0.5)
    assert b.angle == -0.5


def test_a_coupling_is_undone_with_the_request_that_made_it(scene):
    robot, (a, b, c) = coupled_finger(scene)
    with pytest.raises(RuntimeError):
        with scene.journal.transaction():
            b.follow(a, 3.0)
            a.set_angle(-0.4)
            raise RuntimeError("the request fails later")
    assert (a.following, b.following, a.angle, b.angle) == (None, None, 0.0, 0.0)
    a.set_angle(-0.4)
    assert b.angle == 0.0


def _lifted_box(scene, scale=1.0, flipped=False):
    """A robot whose slider (axis y, 0 to 2) carries a box, at (1, 3, 0)."""
    robot, slider = Robot(scene, "r"), Slider(scene, "s", "y", 0, 2, 0)
    box = Box(scene, "b", 0.5, 0.5, 0.5)
    robot.attach_chain(slider, box)
    robot.set_position((1.0, 3.0, 0.0))
    robot.set_scale((scale,) * 3)
    slider.flip(flipped)
    return robot, slider, box


@pytest.mark.parametrize("scale", [1.0, 2.5])
def test_a_slider_moves_what_hangs_on_it_by_lengths_in_the_scene_whatever_the_scale(scene, scale):
    _, slider, box = _lifted_box(scene, scale)
    slider.set_angle(1.5)
    assert box.world_pose()[0] == pytest.approx((1.0, 4.5, 0.0))  # 1.5 scene units up
    assert box.world_pose()[1] == pytest.approx(math3d.IDENTITY)  # and not turned
    slider.set_angle(9)
    assert slider.get_angle() == 2  # clamped as any motor
    scene.tick(1 / 60)  # the physics puts it where the tree does
    assert scene.bodies.physics.part_poses("r")[1][0][0] == pytest.approx((1.0, 5.0, 0.0))
    assert slider.properties()["slides"] and "slides" not in Motor(scene, "m", "y").properties()


def test_a_flipped_slider_moves_the_other_way(scene):
    _, slider, box = _lifted_box(scene, flipped=True)
    slider.set_angle(1.0)
    assert box.world_pose()[0] == pytest.approx((1.0, 2.0, 0.0))


def test_a_slider_lifts_its_load_in_dynamic_mode_and_its_partless_robot_stays_put(scene):
    # on the least mass a robot without parts gets, its mount sank by half the block's size
    # under it: the load reaches the base through the solver alone
    robot, slider, box = _lifted_box(scene, 2.0)
    scene.set_physics("dynamic")
    slider.set_angle(0.5)
    for _ in range(120):
        scene.tick(1 / 60)
    assert slider.get_angle() == pytest.approx(0.5, abs=2e-3)
    assert box.world_pose()[0] == pytest.approx((1.0, 3.5, 0.0), abs=2e-3)
    assert slider.get_max_torque() == DEFAULT_MAX_FORCE  # newtons


def _arm(scene, reach):
    """A robot whose MotorZ carries a 0.1 kg box ``reach`` along x from the joint."""
    robot, motor = Robot(scene, "r"), MotorZ(scene, "m")
    arm = Box(scene, "arm", 0.5, 0.2, 0.2)
    robot.attach_chain(motor, arm)
    arm.set_position((reach, 0.0, 0.0))
    robot.set_position((0.0, 3.0, 0.0))
    scene.set_physics("dynamic")
    arm.set_mass(0.1)
    return motor


@pytest.mark.parametrize("flipped", [False, True])
def test_a_motor_tells_the_torque_it_holds_its_arm_level_with(scene, flipped):
    motor = _arm(scene, 1.0)
    motor.flip(flipped)
    assert motor.get_torque() == 0.0  # not driven yet
    for _ in range(60):
        scene.tick(1 / 60)
    assert motor.get_angle() == pytest.approx(0.0, abs=0.02)
    # gravity turns the arm about -z with m·g·r: the motor holds it with as much about +z
    holding = 0.1 * 9.81 * 1.0 * scene.physics.unit  # N·m (the reach in metres)
    assert motor.get_torque() == pytest.approx(-holding if flipped else holding, rel=0.05)
    scene.set_physics("kinematic")
    assert motor.get_torque() == 0.0  # motors jump to their angles: no effort


def test_a_motor_moves_no_faster_than_its_speed_bound(scene):
    motor = _arm(scene, 0.0)  # balanced: gravity turns it neither way
    assert motor.get_max_speed() == math.inf
    motor.set_max_speed(0.5).set_angle(1.0)
    assert motor.get_speed() == 0.0  # not driven yet
    for _ in range(30):  # half a second
        scene.tick(1 / 60)
    assert motor.get_angle() == pytest.approx(0.25, abs=0.02)  # 0.5 rad/s
    assert motor.get_speed() == pytest.approx(0.5, rel=0.05)  # and reads so
    robot = motor.root()
    assert robot.get_speeds() == [motor.get_speed()] and robot.get_torques() == [motor.get_torque()]
    motor.set_max_speed(math.inf)
    for _ in range(30):
        scene.tick(1 / 60)
    assert motor.get_angle() == pytest.approx(1.0, abs=0.02)  # as fast as its torque allows
    assert abs(motor.get_speed()) < 0.05  # there, and still
    scene.set_physics("kinematic")
    assert robot.get_speeds() == [0.0] == robot.get_torques()
