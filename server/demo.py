"""The live demo of `make run`: the manual's three Diggers (Step 5), driven by the server."""

from __future__ import annotations

import math
from itertools import count
from typing import Callable

from .core.motor import MotorZ
from .core.parts import EdgedFinger
from .core.robot import Robot
from .core.scene import Scene

# (speed, z position) of robots A, B and C in the manual.
DIGGERS = ((2.0, 1.0), (3.0, 0.0), (4.0, -1.0))


def build_digger(scene: Scene, ids: Callable[[], str], speed: float) -> Robot:
    """The manual's ``Digger``: three customised motors and fingers in a chain."""
    robot = Robot(scene, ids())
    robot.speed = speed  # type: ignore[attr-defined]
    robot.attach_chain(
        MotorZ(scene, ids(), -0.7, 0.7, 0, 0.2, 0.6),
        EdgedFinger(scene, ids(), 1, 1, 0.1),
        MotorZ(scene, ids(), -1.6, 0, 0, 0.4, 0.3),
        EdgedFinger(scene, ids(), 2),
        MotorZ(scene, ids(), -1.6, 0, 0, 0.4, 0.2),
        EdgedFinger(scene, ids(), 0.7, 0.1),
    )
    return robot


def dig(robot: Robot, time: float) -> None:
    """The manual's ``dig(time)``."""
    t = time * robot.speed  # type: ignore[attr-defined]
    robot.set_angles(-0.7 * math.sin(t + 3), -1.6 * (0.5 + 0.5 * math.sin(t + 1)),
                     -1.6 * (0.5 + 0.5 * math.sin(t)))


def setup_diggers(scene: Scene) -> Callable[[Scene, float], None]:
    """Put the three Diggers into ``scene``; the returned animator makes them dig."""
    numbers = count(1)
    robots = []
    for speed, z in DIGGERS:
        robot = build_digger(scene, lambda: f"demo.{next(numbers)}", speed)
        robot.set_position((0.0, 0.0, z))
        robots.append(robot)

    def animate(scene: Scene, time: float) -> None:
        for robot in robots:
            if robot.id in scene.nodes:
                dig(robot, time)
    return animate
