"""Motor limits, clamping, flipping and naming as spec/parts.md says."""

import math

import pytest

from server.core.kit import math3d
from server.core.model.motor import Motor, MotorX, MotorY, MotorZ
from server.errors import OutOfRange


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
