"""SceneMeshes, scale, visibility and setTransforms from the Python client, against a real server."""

from __future__ import annotations

import math

import pytest
import requests

import virtual_prosthetics as vp

DOWN = (math.pi, 0, 0)


def down_sensor(x=0.0, height=3.0):
    sensor = vp.Sensor()
    sensor.set_position(x, height, 0)
    sensor.set_rotation(*DOWN)
    return sensor


def test_a_shape_is_sensed_and_moved_with_set_transforms(scene, server, scene_name):
    wall = vp.SceneMesh({"kind": "box", "size": [1, 1, 1]}, "orange")
    marker = vp.SceneMesh({"kind": "sphere", "radius": 0.25})
    sensor = down_sensor()
    assert sensor.sense_distance() == pytest.approx(2.5, abs=1e-4)  # the box's top at 0.5
    vp.set_transforms({wall: [5, 0, 0, 0, 0, 0, 1], marker: [0, 1, 0, 0, 0, 0, 1, 2, 2, 2]})
    assert sensor.sense_distance() == pytest.approx(1.5, abs=1e-4)  # sphere of radius 0.5 at 1
    scene.sync()
    snapshot = requests.get(f"{server.http}/api/scenes/{scene_name}/snapshot").json()
    shown = {n["id"]: n for n in snapshot["nodes"]}
    assert shown[wall.id]["position"] == [5, 0, 0]
    assert shown[marker.id]["scale"] == [2, 2, 2]
    assert shown[wall.id]["color"] == "orange"


def test_a_bad_transform_moves_nothing(scene):
    ball = vp.Ball(0.5)
    ball.set_position(0, 2, 0)
    with pytest.raises(vp.ServerError, match="ghost"):
        vp.set_transforms({ball: [9, 9, 9, 0, 0, 0, 1], "ghost": [0, 0, 0, 0, 0, 0, 1]})
        scene.sync()
    sensor = down_sensor()
    assert sensor.sense_distance() == pytest.approx(0.5, abs=1e-4)  # still at (0, 2, 0)


def test_a_hidden_part_is_still_sensed_and_a_scaled_one_is_bigger(scene):
    box = vp.Box(1, 1, 1)
    box.set_position(0, 1, 0)
    box.set_visible(False)
    sensor = down_sensor()
    assert sensor.sense_distance() == pytest.approx(1.5, abs=1e-4)
    box.set_scale([1, 2, 1])
    assert sensor.sense_distance() == pytest.approx(1.0, abs=1e-4)
