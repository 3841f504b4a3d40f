"""Collision sensors, after the 1.0 example: a row of arms sweeps until each one's fingertip
feels a box.

    .venv/bin/python clients/python/examples/collision_sensors.py [ws://127.0.0.1:8000] [scene]

Each arm has a hidden sensor on its tip and watches it, so the animation loop reads
``sense_collision()`` from the frames, with no round trip per arm.
"""

from __future__ import annotations

import math
import random
import sys

import virtual_prosthetics as vp

PI = math.pi
ARMS = 11


class TouchRobot(vp.Robot):
    """An arm of two motors, a finger, a motor and a tip with a sensor on it."""

    def __init__(self) -> None:
        super().__init__()
        tip = vp.EdgedTip(0.75)
        self.attach_chain(vp.MotorZ(PI / 2, -PI / 2, 0, 0.2, 0.3), vp.MotorY(-1, 1, 0, 0.2, 0.1),
                          vp.EdgedFinger(0.75), vp.MotorZ(0.0, -PI / 2, 0, 0.25, 0.08), tip)
        self.sensor = vp.Sensor(False).attach_to_slot(tip)
        self.sensor.watch()


def spread(i: int, count: int) -> float:
    """Position i of count, evenly from -4 to 4 (1.0's mapLinear)."""
    return -4 + 8 * i / (count - 1)


def build(rng: random.Random) -> tuple[list[TouchRobot], list[vp.Box]]:
    """The arms in a row, each turned at random, and twice as many boxes of random tilt."""
    robots = []
    for i in range(ARMS):
        robot = TouchRobot()
        robot.set_position(0, 0, spread(i, ARMS))
        robot.set_angles(0.5, 0.8 * rng.random() - 0.4, 0)
        robots.append(robot)
    boxes = []
    for i in range(2 * ARMS):
        box = vp.Box(0.1, 2, 0.3)
        box.set_position(0.8, rng.random() - 0.5, spread(i, 2 * ARMS))
        box.set_rotation(0.4 * rng.random() - 0.2, rng.random() - 0.5, 0.4 * rng.random() - 0.2)
        boxes.append(box)
    vp.set_camera_position(-7, 7, 0)
    return robots, boxes


def sweep(robots: list[TouchRobot], speed: float = 1.0, seconds: float = 20.0) -> None:
    """Turn every arm towards the boxes until its sensor reports a collision."""
    def loop(t: float, dt: float) -> None:
        for robot in robots:
            if robot.sensor.sense_collision():
                continue
            angle = robot.get_angle(0)
            robot.set_angle(0, angle - speed * dt / 2)
            robot.set_angle(2, angle - speed * dt)

    vp.set_animation(loop)
    start = vp.get_time()
    while vp.get_time() - start < seconds:
        vp.run(0.25)
        if all(robot.sensor.sense_collision() for robot in robots):
            return


def main(url: str = "ws://127.0.0.1:8000", scene: str = "default") -> None:
    vp.connect(url, scene=scene)
    robots, boxes = build(random.Random())
    sweep(robots)
    for i, robot in enumerate(robots):
        touched = [obj for obj in robot.sensor.sense_objects(exact=True) if obj in boxes]
        print(f"arm {i}: angle {robot.get_angle(0):+.2f}, touching {touched}")
    vp.run()  # keep the scene up for the viewers until the server goes away


if __name__ == "__main__":
    main(*sys.argv[1:3])
