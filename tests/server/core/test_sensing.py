"""Sensor readings along +Y: distances, the touch ramp, what rays see and what they do not."""

import math

import pytest

from server.core.motor import MotorX
from server.core.parts import Ball, Box, EdgedFinger
from server.core.sensor import Sensor

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
