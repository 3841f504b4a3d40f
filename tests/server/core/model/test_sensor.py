"""Sensors: their options, the part whose contacts they report, watching."""

import math

import pytest

from server.core.model.parts import Box, EdgedFinger, EdgedTip
from server.core.model.robot import Robot
from server.core.model.sensor import Sensor
from server.core.model.watches import LASER

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
    assert hidden.describe()["visible"] is False  # its pad is described, and not drawn
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
