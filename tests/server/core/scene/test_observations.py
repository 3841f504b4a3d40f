"""What a tick observes: contacts that begin and end, readings of watched sensors."""

import math

import pytest

from server.core.model.parts import Box, EdgedFinger
from server.core.model.robot import Robot
from server.core.model.sensor import Sensor


def frame_of(messages):
    return next(m for m in messages if m["op"] == "frame")


def contacts_of(messages):
    return frame_of(messages).get("contacts")


def test_contacts_begin_and_end_once_each_tick_they_change(scene):
    finger = EdgedFinger(scene, "f")
    finger.set_position((0, 1, 0))
    box = Box(scene, "b", 1, 0.1, 0.1)
    box.set_position((0, 1.5, 0))
    assert contacts_of(scene.tick(0.1)) == {"begin": [["b", "f"]], "end": []}
    assert contacts_of(scene.tick(0.1)) is None  # still touching: no news
    assert scene.snapshot()["contacts"] == [["b", "f"]]
    box.set_position((0, -0.01, 0))  # off the finger, onto the ground
    assert contacts_of(scene.tick(0.1)) == {"begin": [["b", "ground"]], "end": [["b", "f"]]}
    assert scene.snapshot()["contacts"] == [["b", "ground"]]


def test_deleted_or_hidden_parts_end_their_contacts(scene):
    robot = Robot(scene, "r")
    finger = EdgedFinger(scene, "f")
    robot.attach_chain(finger)
    robot.set_position((0, -0.5, 0))
    box = Box(scene, "b", 0.5, 0.5, 0.5)
    box.set_position((0, 0, 0))
    assert contacts_of(scene.tick(0.1))["begin"] == [["b", "f"], ["b", "ground"],
                                                    ["f", "ground"]]
    robot.set_position()  # taken out of the scene
    assert contacts_of(scene.tick(0.1)) == {"begin": [], "end": [["b", "f"], ["f", "ground"]]}
    scene.delete(box)
    assert contacts_of(scene.tick(0.1)) == {"begin": [], "end": [["b", "ground"]]}


def test_frames_carry_readings_of_watched_and_laser_sensors(scene):
    watched, laser, quiet = Sensor(scene, "w"), Sensor(scene, "l", True, True), Sensor(scene, "q")
    for sensor, x in ((watched, 0), (laser, 1), (quiet, 2)):
        sensor.set_position((x, 2, 0))
        sensor.set_rotation(math.pi, 0, 0)
    watched.watch(client="c1")
    frame = frame_of(scene.tick(0.1))
    assert set(frame["sensors"]) == {"w", "l"}
    assert frame["sensors"]["w"] == {"distance": pytest.approx(2.0), "touch": 0.0,
                                     "position": [0, 2, 0], "objects": [], "force": 0.0,
                                     "contacts": []}
    watched.set_rotation(0, 0, 0)
    assert frame_of(scene.tick(0.1))["sensors"]["w"]["distance"] == "Infinity"
    scene.delete(laser)
    assert set(frame_of(scene.tick(0.1))["sensors"]) == {"w"}
    assert scene.watches.ids() == ["w"]
