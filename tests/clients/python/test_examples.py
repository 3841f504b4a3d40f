"""The Python examples run against a real server and do what they say."""

from __future__ import annotations

import importlib.util
import random
from pathlib import Path

import pytest

import virtual_prosthetics as vp

EXAMPLES = Path(__file__).resolve().parents[3] / "clients" / "python" / "examples"


def load(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("seed", [1, 2])
def test_collision_sensors_every_arm_stops_at_a_box(server, scene_name, seed):
    example = load("collision_sensors")
    scene = vp.connect(server.ws, scene=f"{scene_name}-{seed}")
    try:
        robots, boxes = example.build(random.Random(seed))
        with scene.paused():  # stepped: each animation step a tick, however loaded the machine
            example.sweep(robots, speed=3.0, seconds=15.0)
        stopped = [robot.get_angle(0) for robot in robots]
        for robot in robots:
            touched = robot.sensor.sense_objects(exact=True)
            assert any(obj in boxes for obj in touched), (robot, touched)
            assert "ground" not in touched
        assert all(-1.5 < angle < 0.5 for angle in stopped)  # each turned, none to its limit
        vp.run(0.3)
        assert [robot.get_angle(0) for robot in robots] == stopped  # and they stay put
    finally:
        scene.close()
