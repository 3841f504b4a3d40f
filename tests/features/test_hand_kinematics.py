"""Fingertips of every hand, left and right, where forward kinematics computed here straight
from spec/parts.md puts them (1e-6), and a right hand the mirror image of a left one."""

from __future__ import annotations

import math

import numpy as np
import pytest

from server.core.model.hands import AnthroHand, EdgedHand, RoundHand

PI = math.pi
POSITION, ROTATION = (1.0, 2.0, -0.5), (0.3, -0.4, 0.2)  # the robot's pose (XYZ Euler)


# --- rotations, as the spec defines them (intrinsic, matrix = R1·R2·R3 for order "123") ---

def axis_matrix(axis: str, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return {"x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
            "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])}[axis]


def euler(angles, order="XYZ") -> np.ndarray:
    by_axis = dict(zip("XYZ", angles))
    matrix = np.eye(3)
    for axis in order:
        matrix = matrix @ axis_matrix(axis.lower(), by_axis[axis])
    return matrix


class Frame:
    """A world transform walked down a chain: translate, rotate, read points."""

    def __init__(self, position=(0, 0, 0), rotation=np.eye(3)):
        self.p, self.r = np.array(position, float), rotation

    def then(self, position=(0, 0, 0), rotation=np.eye(3)) -> "Frame":
        return Frame(self.p + self.r @ np.array(position, float), self.r @ rotation)

    def motor(self, axis: str, angle: float, flipped: bool, slot=(0, 0, 0)) -> "Frame":
        """Through a motor at this frame to its slot 0."""
        return self.then(rotation=axis_matrix(axis, -angle if flipped else angle)).then(slot)


# --- the hands of spec/parts.md -------------------------------------------------------------

def edged_palm_slot(i: int, left: bool):
    s, w, inset, length = (1 if left else -1), 0.7, 1.4 / 8, 1.4
    p = [(-s * w + s * inset, 0), (s * w - 2 * s * inset, 0), (s * w, 2 * inset), (s * w, length),
         (-s * w, length), (-s * w, length / 2)]
    a, b, k = [(2, 3, 1 / 4), (3, 4, 1 / 8), (3, 4, 3 / 8), (3, 4, 5 / 8), (3, 4, 7 / 8)][i]
    (xa, ya), (xb, yb) = p[a], p[b]
    position = (xa * (1 - k) + xb * k, ya * (1 - k) + yb * k, 0)
    return position, euler((0, PI / 2, (1 + s) * PI / 2 + math.atan2(yb - ya, xb - xa)), "ZXY")


def round_palm_slot(i: int, left: bool, anthro: bool):
    f, length = (1 if left else -1), 1.4
    if i == 0 and anthro:
        return ((0.32 * f * length, 0.16 * length, 0),
                euler((PI / 2, 0.75 * PI + (0 if left else PI / 2), -0.5 * f * PI), "XYZ"))
    if i == 0:
        return ((0.53 * f * length, 0.50 * length, 0),
                euler((PI / 2 * (1 + f), -f * PI / 2, PI / 2 + 0.7 * f), "ZXY"))
    x, y, k = [(0.36, 1.13, -3), (0.12, 1.17, -1), (-0.12, 1.16, 1), (-0.36, 1.09, 3)][i - 1]
    return (x * f * length, y * length, 0), euler((0, PI / 2, k * f * PI / 180), "ZXY")


def flex_chain(frame: Frame, angles, lengths) -> np.ndarray:
    """MotorZ → finger of each length, …; the tip's slot (0, last length, 0)."""
    for angle, length in zip(angles, lengths):
        frame = frame.motor("z", angle, False).then((0, length, 0))
    return frame.p


def edged_tips(angles, left: bool, robot: Frame) -> list[np.ndarray]:
    tips = []
    for i, size in enumerate([1, 1, 1.1, 1, 0.8]):
        spread, *flex = angles[4 * i:4 * i + 4]
        frame = robot.then(*edged_palm_slot(i, left)).motor("x", spread, left)
        tips.append(flex_chain(frame, flex, [size, 0.5, 0.5]))
    return tips


def round_tips(angles, left: bool, robot: Frame) -> list[np.ndarray]:
    tips = []
    for i in range(5):
        spread, *flex = angles[4 * i:4 * i + 4]
        frame = robot.then(*round_palm_slot(i, left, anthro=False))
        frame = frame.motor("y", spread, not left, (0, 0.1, 0)) if i == 0 else frame.motor("x", spread, left)
        tips.append(flex_chain(frame, flex, [0.8, 0.5, 0.5]))
    return tips


def anthro_tips(angles, left: bool, robot: Frame) -> list[np.ndarray]:
    f, length = (1 if left else -1), 1.4
    palm, thumb, twist, *flex = angles[:6]
    frame = robot.then(*round_palm_slot(0, left, anthro=True)).motor("z", palm, not left)
    frame = frame.then((0, -0.2 * length, 0.06 * length), euler((PI / 2, (1 - f) * PI / 2, 0)))
    frame = frame.motor("x", thumb, not left).motor("y", twist, not left, (0, 0.2, 0))
    tips = [flex_chain(frame, flex, [0.8, 0.5, 0.5])]
    for i in range(1, 5):
        spread, *flex = angles[4 * i + 2:4 * i + 6]
        frame = robot.then(*round_palm_slot(i, left, anthro=True)).motor("x", spread, left)
        tips.append(flex_chain(frame, flex, [0.8, 0.5, 0.5]))
    return tips


HANDS = [(EdgedHand, edged_tips), (RoundHand, round_tips), (AnthroHand, anthro_tips)]
POSES = [lambda h: None,
         lambda h: h.flex_fingers(0.6),
         lambda h: (h.flex_fingers(1.2), h.spread_fingers(0.4, True)),
         lambda h: (h.flex_finger(0, 0.3), h.spread_finger(2, -0.3), h.flex_finger(4, 1.5),
                    h.spread_fingers(-0.2, True))]


def fingertips(hand) -> list[tuple[float, ...]]:
    """The server's fingertips: the world position of each finger's last slot."""
    tips = [p for p in hand.get_parts() if p.type_name in ("EdgedFinger", "EdgedTip", "RoundFinger")][2::3]
    return [tip.slots[0].world_pose()[0] for tip in tips]


@pytest.mark.parametrize("kind, expected", HANDS)
@pytest.mark.parametrize("left", [True, False])
@pytest.mark.parametrize("pose", range(len(POSES)))
def test_fingertips_are_where_the_spec_puts_them(scene, kind, expected, left, pose):
    hand = kind(scene, "h", left)
    hand.set_position(POSITION)
    hand.set_rotation(*ROTATION)
    POSES[pose](hand)
    robot = Frame(POSITION, euler(ROTATION))
    want = expected(hand.get_angles(), left, robot)
    got = fingertips(hand)
    assert len(got) == 5
    for finger, (a, b) in enumerate(zip(got, want)):
        assert a == pytest.approx(tuple(b), abs=1e-6), (kind.__name__, left, pose, finger)


@pytest.mark.parametrize("kind", [EdgedHand, RoundHand, AnthroHand])
@pytest.mark.parametrize("pose", range(len(POSES)))
def test_a_right_hand_is_the_left_one_mirrored_in_x(scene, kind, pose):
    left, right = kind(scene, "l", True), kind(scene, "r", False)
    for hand in (left, right):
        POSES[pose](hand)
    assert left.get_angles() == right.get_angles()
    for a, b in zip(fingertips(left), fingertips(right)):
        assert (-a[0], a[1], a[2]) == pytest.approx(b, abs=1e-12)
    for a, b in zip(left.get_parts(), right.get_parts()):  # every part, not only the tips
        (pa, _), (pb, _) = a.world_pose(), b.world_pose()
        assert (-pa[0], pa[1], pa[2]) == pytest.approx(pb, abs=1e-12)
