"""The live demos of `make run`: six hands making gestures (the ``default`` scene) and the
manual's three Diggers (Step 5, scene ``diggers``), driven by the server."""

from __future__ import annotations

import math
from itertools import count
from typing import Callable

from .core.model.hands import AnthroHand, EdgedHand, Hand, RoundHand
from .core.model.motor import MotorZ
from .core.model.parts import EdgedFinger
from .core.model.robot import Robot
from .core.scene.scene import Scene
from .web.process.scene_start import SERVER_OWNER, SceneSetup

# (speed, z position) of robots A, B and C in the manual.
DIGGERS = ((2.0, 1.0), (3.0, 0.0), (4.0, -1.0))


def build_digger(scene: Scene, ids: Callable[[], str]) -> Robot:
    """The manual's ``Digger``: three customised motors and fingers in a chain."""
    robot = Robot(scene, ids())
    robot.attach_chain(
        MotorZ(scene, ids(), -0.7, 0.7, 0, 0.2, 0.6),
        EdgedFinger(scene, ids(), 1, 1, 0.1),
        MotorZ(scene, ids(), -1.6, 0, 0, 0.4, 0.3),
        EdgedFinger(scene, ids(), 2),
        MotorZ(scene, ids(), -1.6, 0, 0, 0.4, 0.2),
        EdgedFinger(scene, ids(), 0.7, 0.1),
    )
    return robot


def dig(robot: Robot, time: float, speed: float) -> None:
    """The manual's ``dig(time)`` of a Digger of this speed."""
    t = time * speed
    robot.set_angles(-0.7 * math.sin(t + 3), -1.6 * (0.5 + 0.5 * math.sin(t + 1)),
                     -1.6 * (0.5 + 0.5 * math.sin(t)))


def setup_diggers(scene: Scene) -> Callable[[Scene, float], None]:
    """Put the three Diggers into ``scene``; the returned animator makes them dig."""
    numbers = count(1)
    speeds = {}
    for speed, z in DIGGERS:
        robot = build_digger(scene, lambda: f"{SERVER_OWNER}.{next(numbers)}")
        robot.set_position((0.0, 0.0, z))
        robot.share()
        speeds[robot.id] = speed

    def animate(scene: Scene, time: float) -> None:
        # by id: a scene restored from a document has new objects of the same ids
        for robot_id, speed in speeds.items():
            robot = scene.nodes.get(robot_id)
            if isinstance(robot, Robot):
                dig(robot, time, speed)
    return animate


# The hands of the default demo: (class, x); each kind has a left hand behind (z < 0)
# and a right hand in front.
HANDS = ((EdgedHand, -3.0), (RoundHand, 0.0), (AnthroHand, 3.0))
GESTURE_SECONDS = 3.0


def gesture(hand: Hand, time: float) -> None:
    """Open, fist, spread, point, in turn, each easing into the next."""
    phase, within = divmod(time / GESTURE_SECONDS, 1.0)
    ease = 0.5 - 0.5 * math.cos(math.pi * min(1.0, within * 2))
    poses = [(0.0, 0.0, 0.0), (1.3, 1.3, 0.0), (0.0, 0.0, 0.5), (1.3, 0.0, 0.0)]
    (flex, index_flex, spread), (flex2, index2, spread2) = (
        poses[int(phase) % 4], poses[(int(phase) + 1) % 4])
    flex, index_flex, spread = (a + (b - a) * ease for a, b in
                                ((flex, flex2), (index_flex, index2), (spread, spread2)))
    hand.spread_fingers(spread, True)
    for finger in range(5):
        hand.flex_finger(finger, index_flex if finger == 1 else flex)


def setup_hands(scene: Scene) -> Callable[[Scene, float], None]:
    """A left and a right hand of each kind; the returned animator makes them gesture."""
    hands = []
    for kind, x in HANDS:
        for left, z in ((True, -1.2), (False, 1.2)):
            side = "left" if left else "right"
            hand = kind(scene, f"{SERVER_OWNER}.{kind.type_name}-{side}", left)
            hand.set_position((x, 0.2, z))
            hand.share()  # anyone's motor panel may move it
            hands.append(hand.id)
    scene.set_camera_position((0.0, 5.0, 15.0))
    scene.set_camera_target((0.0, 1.6, 0.0))

    def animate(scene: Scene, time: float) -> None:
        for k, hand_id in enumerate(hands):
            hand = scene.nodes.get(hand_id)  # by id, as the Diggers
            if isinstance(hand, Hand):
                gesture(hand, time + 0.4 * k)
    return animate


DEMOS: dict[str, SceneSetup] = {"default": setup_hands, "diggers": setup_diggers}
