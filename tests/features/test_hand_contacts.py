"""Hands in contact: at rest and spread they touch nothing of their own; a fist touches its
palm; two hands pressed together touch; neighbouring finger segments never do."""

import math

import pytest

from server.core.model.gltf_parts import RoundFinger
from server.core.model.hands import AnthroHand, EdgedHand, RoundHand


def _touching_within(scene, hand):
    """Pairs of the hand's own parts that touch (sorted ids)."""
    parts = {p.id for p in hand.get_parts() if p.physical}
    return {tuple(sorted((a, b))) for a in parts for b in scene.bodies.touching(scene.get(a)) if b in parts}


def _physical_neighbours(motor):
    below, above = motor.parent, next(iter(motor.children), None)
    while below is not None and not below.physical:
        below = below.parent
    while above is not None and not above.physical:
        above = next(iter(above.children), None)
    return below, above


@pytest.mark.parametrize("kind", [RoundHand, AnthroHand])
@pytest.mark.parametrize("left", [True, False])
def test_hands_at_rest_and_spread_open_touch_nothing_of_their_own(scene, kind, left):
    hand = kind(scene, "h", left)
    assert _touching_within(scene, hand) == set()
    hand.flex_fingers(0)
    hand.spread_fingers(1, True)
    assert _touching_within(scene, hand) == set()


@pytest.mark.parametrize("kind", [RoundHand, AnthroHand])
def test_finger_segments_never_touch_their_neighbours_whatever_the_joint_angle(scene, kind):
    hand = kind(scene, "h")
    joints = [m for m in hand.get_motors() if m.name in ("middle", "distal")]
    assert len(joints) == 10
    for motor in joints:
        below, above = _physical_neighbours(motor)
        assert type(below) is type(above) is RoundFinger
        for step in range(11):
            motor.set_angle(motor.min + (motor.max - motor.min) * step / 10)
            assert above.id not in scene.bodies.touching(below), (motor.id, motor.get_angle())


@pytest.mark.parametrize("kind, fingers", [(RoundHand, 5), (AnthroHand, 4)])
def test_a_fist_touches_its_palm_left_and_right_alike(scene, kind, fingers):
    hands = [kind(scene, "l", True), kind(scene, "r", False)]
    for x, hand in zip((-3, 3), hands):
        hand.set_position((x, 2, 0))  # apart, and off the ground
        hand.flex_fingers(math.pi / 2)
    touched = [sorted(i.split("/")[1] for i in scene.bodies.touching(hand.get_parts()[0]))
               for hand in hands]
    assert touched[0] == touched[1]  # the right hand is the left one's mirror image
    assert len(touched[0]) >= fingers  # every folded finger (not its thumb, for anthro)


@pytest.mark.parametrize("kind", [EdgedHand, RoundHand, AnthroHand])
def test_two_hands_pressed_palm_to_palm_touch(scene, kind):
    left, right = kind(scene, "l", True), kind(scene, "r", False)
    right.set_rotation(0, math.pi, 0)  # the right hand faces the left one: a clap
    palms = left.get_parts()[0], right.get_parts()[0]
    for hand in (left, right):
        hand.flex_fingers(0)  # flat hands: only the palms can meet
    for half_gap, touching in ((0.16, False), (0.1505, False), (0.1495, True), (0.1, True)):
        left.set_position((0, 1, half_gap))   # palms are 0.3 thick: faces at ±0.15
        right.set_position((0, 1, -half_gap))
        assert (palms[1].id in scene.bodies.touching(palms[0])) is touching, half_gap
