"""Sensors: rays along their +Y, touch over the pad, and the contacts of their part."""

import math

import pytest

from server.core.motor import MotorX
from server.core.parts import Ball, Box, EdgedFinger, EdgedTip
from server.core.robot import Robot
from server.core.sensor import Sensor
from server.core.watches import LASER

DOWN = (math.pi, 0, 0)  # turns the sensing direction +Y to -Y


def sensor_at(scene, height, name="s", rotation=DOWN):
    sensor = Sensor(scene, name)
    sensor.set_position((0, height, 0))
    sensor.set_rotation(*rotation)
    return sensor


@pytest.mark.parametrize("height", [0.05, 0.3, 1.0, 2.5, 40.0])
def test_sensor_pointing_down_reads_its_height(scene, height):
    assert sensor_at(scene, height).sense_distance() == pytest.approx(height, abs=1e-4)


def test_sensor_pointing_up_at_nothing_reads_infinity(scene):
    assert sensor_at(scene, 1.0, rotation=(0, 0, 0)).sense_distance() == math.inf


def test_hits_nearer_than_the_pad_are_ignored(scene):
    low = sensor_at(scene, 0.03)
    assert low.sense_distance() == math.inf  # the ground is within 0.05, nothing beyond
    Box(scene, "shelf", 1, 0.1, 1).set_position((0, 0.5, 0))
    low.set_rotation(0, 0, 0)
    assert low.sense_distance() == pytest.approx(0.42, abs=1e-4)  # underside at 0.45


@pytest.mark.parametrize("height, touch", [(0.0, 1.0), (0.01, 0.8), (0.025, 0.5),
                                           (0.05, 0.0), (0.2, 0.0)])
def test_touch_ramps_from_zero_to_one_over_the_last_five_centimetres(scene, height, touch):
    assert sensor_at(scene, height).sense_touch() == pytest.approx(touch, abs=1e-4)


def test_motors_and_sensors_are_transparent_parts_are_not(scene):
    sensor = sensor_at(scene, 2.0)
    MotorX(scene, "motor", 0, 1, 0, 1, 1).set_position((0, 1, 0))
    sensor_at(scene, 1.5, "other")
    assert sensor.sense_distance() == pytest.approx(2.0, abs=1e-4)
    Ball(scene, "ball", 0.25).set_position((0, 1, 0))
    assert sensor.sense_distance() == pytest.approx(0.75, abs=1e-4)


def test_direction_follows_the_slot_the_sensor_is_attached_to(scene):
    finger = EdgedFinger(scene, "f")
    finger.set_position((0, 1, 0))
    finger.set_rotation(0, 0, math.pi / 2)  # the finger, and its slot, point along -X
    sensor = Sensor(scene, "s").attach_to_slot(finger)
    Box(scene, "wall", 0.2, 3, 3).set_position((-3, 1, 0))
    assert sensor.sense_position() == pytest.approx((-1, 1, 0))
    assert sensor.sense_distance() == pytest.approx(1.9, abs=1e-4)


def test_a_sensor_on_a_tip_senses_past_its_own_tip(scene):
    tip = EdgedTip(scene, "tip")
    tip.set_position((0, 1, 0))
    tip.set_rotation(math.pi, 0, 0)  # pointing down: its slot is at y = 0, its end 0.003 up
    sensor = Sensor(scene, "s").attach_to_slot(tip)
    assert sensor.sense_position() == pytest.approx((0, 0, 0))
    assert sensor.sense_touch() == pytest.approx(1.0)
    assert sensor.sense_objects() == []
    tip.set_position((0, 0.995, 0))
    assert sensor.sense_objects() == ["ground"] and sensor.sense_collision()


def test_box_across_a_finger_is_sensed_until_it_moves_away(scene):
    finger = EdgedFinger(scene, "f")
    finger.set_position((0, 1, 0))
    sensor = Sensor(scene, "s").attach_to_slot(finger)
    box = Box(scene, "b", 1, 0.1, 0.1)
    box.set_position((0, 1.5, 0))
    assert sensor.sense_collision() is True
    assert sensor.sense_objects() == ["b"]
    assert sensor.sense_object(box) is True and sensor.sense_object("ground") is False
    box.set_position((3, 1.5, 0))
    assert sensor.sense_collision() is False and sensor.sense_objects() == []
    assert sensor.sense_object(box) is False


def test_ground_contact_counts(scene):
    finger = EdgedFinger(scene, "f")
    sensor = Sensor(scene, "s").attach_to_slot(finger)
    finger.set_position((0, 0.01, 0))
    assert sensor.sense_objects() == []
    finger.set_position((0, -0.01, 0))
    assert sensor.sense_objects() == ["ground"] and sensor.sense_object("ground")


def test_a_sensor_without_a_part_above_it_senses_no_contacts(scene):
    robot = Robot(scene, "r")
    sensor = Sensor(scene, "s").attach_to_slot(robot)
    robot.set_position((0, -1, 0))
    assert sensor.host() is None and sensor.sense_collision() is False
    assert sensor.sense_position() == (0, -1, 0)


def test_pad_and_laser_options(scene):
    plain, hidden = Sensor(scene, "a"), Sensor(scene, "b", False, True)
    coloured = Sensor(scene, "c", True, "#00ff00")
    assert plain.describe()["geometry"]["kind"] == "dome"
    assert plain.describe()["physical"] is False and plain.laser_color is None
    assert "geometry" not in hidden.describe() and hidden.describe()["visible"] is False
    assert hidden.laser_color == "crimson" and coloured.laser_color == "#00ff00"
    assert scene.watches.ids() == ["b", "c"]  # frames carry what viewers draw lasers from
    assert LASER == "laser"


def test_watching_is_per_client(scene):
    sensor = Sensor(scene, "s")
    sensor.watch(True, client="c1")
    sensor.watch(True, client="c2")
    sensor.watch(False, client="c1")
    assert "s" in scene.watches
    sensor.watch(False, client="c2")
    assert "s" not in scene.watches
