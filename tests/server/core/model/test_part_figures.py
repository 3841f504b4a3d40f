"""The part figures of spec/parts.md as numbers: profiles, slots and motor drawings."""

import math

import numpy as np
import pytest

from server.core.model import part_figures as figures

PI = math.pi


def mirrored(position):
    x, y, z = position
    return (-x, y, z)


def is_convex(profile) -> bool:
    """Every turn of the closed polygon goes the same way."""
    points = np.asarray(profile)
    edges = np.roll(points, -1, axis=0) - points
    after = np.roll(edges, -1, axis=0)
    turns = edges[:, 0] * after[:, 1] - edges[:, 1] * after[:, 0]
    return bool((turns >= -1e-12).all() or (turns <= 1e-12).all())


@pytest.mark.parametrize("tip", [False, True])
@pytest.mark.parametrize("length, thickness", [(1.0, 0.3), (0.8, 0.3), (2.0, 0.1)])
def test_an_edged_finger_profile_is_convex_and_stays_off_both_slot_planes(length, thickness, tip):
    profile = figures.edged_finger_profile(length, thickness, tip)
    ys = [y for _, y in profile]
    assert is_convex(profile)
    assert min(ys) == pytest.approx(figures.EDGE_EPSILON)  # the E of the spec: off the slot plane
    assert max(ys) == pytest.approx(length - figures.EDGE_EPSILON)
    assert max(abs(x) for x, _ in profile) == pytest.approx(thickness / 2)


def test_a_tip_differs_from_a_finger_only_at_its_top():
    finger, tip = (figures.edged_finger_profile(1, 0.3, t) for t in (False, True))
    assert finger[:4] == tip[:4] and finger[6:] == tip[6:] and finger[4:6] != tip[4:6]


def test_the_right_palm_and_its_slots_are_the_left_ones_mirrored_in_x():
    left, right = (figures.edged_palm_profile(side, 1.4, 1.4) for side in (True, False))
    assert right == [(-x, y) for x, y in left]
    for make in (lambda side: figures.edged_palm_slots(side, 1.4, 1.4),
                 lambda side: figures.round_palm_slots(side, 1.4),
                 lambda side: figures.anthro_palm_slots(side, 1.4)):
        lefts, rights = make(True), make(False)
        assert len(lefts) == len(rights) == 5
        for (l_pos, _, _), (r_pos, _, _) in zip(lefts, rights):
            assert r_pos == pytest.approx(mirrored(l_pos))


def test_palm_slots_grow_with_the_palm_and_the_thumbs_comes_first():
    small, big = figures.round_palm_slots(True, 1.0), figures.round_palm_slots(True, 2.0)
    for (a, _, _), (b, _, _) in zip(small, big):
        assert b == pytest.approx(tuple(2 * v for v in a))
    thumb, *fingers = small
    assert thumb[0][1] < min(position[1] for position, _, _ in fingers)  # lower on the palm


def test_edged_palm_slots_lie_on_the_edges_the_spec_names():
    profile = figures.edged_palm_profile(True, 1.4, 1.4)
    for (position, _, order), (a, b, k) in zip(figures.edged_palm_slots(True, 1.4, 1.4),
                                               figures.EDGED_PALM_SLOTS):
        expected = np.asarray(profile[a]) * (1 - k) + np.asarray(profile[b]) * k
        assert position[:2] == pytest.approx(tuple(expected)) and position[2] == 0
        assert order == "ZXY"


@pytest.mark.parametrize("motor_type", sorted(figures.MOTORS))
def test_a_motor_is_drawn_along_its_axis_and_the_y_motor_carries_its_slot_on_top(motor_type):
    figure = figures.MOTORS[motor_type]
    cylinder = figures.motor_cylinder(motor_type, figure.width, figure.height)
    assert cylinder["axis"] == figure.axis and cylinder["sides"] == figure.sides
    slot = figures.motor_slot(figure.axis, figure.height)
    if figure.axis == "y":
        assert slot == (0.0, figure.height, 0.0) and cylinder["length"] == figure.height
        assert cylinder["center"][1] == figure.height / 2  # stands on its origin
    else:
        assert slot == (0.0, 0.0, 0.0) and cylinder["length"] == figure.width


def test_an_edged_thumb_spreads_wider_than_the_fingers_and_the_fingers_open_symmetrically():
    thumb, *fingers = (figures.edged_spread_motor(finger) for finger in range(5))
    assert thumb[:2] == (-1.0, 1.0) and all(motor[:2] == (-0.4, 0.4) for motor in fingers)
    shares = figures.SPREAD_FINGERS  # index to little finger: mirrored about the middle one
    assert shares == tuple(-share for share in reversed(shares))
