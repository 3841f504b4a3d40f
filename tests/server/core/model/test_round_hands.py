"""Round and anthropomorphic hands: chains, motor names and order, and what each method moves."""

import math

import pytest

from server.core.model.hands import AnthroHand, EdgedHand, RoundHand
from server.core.model.part_figures import PALM_JOINT_GAP, round_palm_slots
from server.core.model.mesh_parts import AnthroPalm, AnthroThumb, RoundFinger, RoundPalm, slot_direction

FINGERS = ["Thumb", "Index finger", "Middle finger", "Ring finger", "Little finger"]
FLEX = ["proximal", "middle", "distal"]


def test_round_hand_has_the_specs_twenty_named_motors(scene):
    hand = RoundHand(scene, "h", True)
    names = [m.name for m in hand.get_motors()]
    assert names == [n for finger in FINGERS for n in [finger, *FLEX]]
    types = [m.type_name for m in hand.get_motors()][0::4]
    assert types == ["MotorY", "MotorX", "MotorX", "MotorX", "MotorX"]


def test_anthro_hand_has_the_specs_twenty_two_named_motors(scene):
    hand = AnthroHand(scene, "h", True)
    names = [m.name for m in hand.get_motors()]
    assert names == ["Palm", "Thumb", "twist", *FLEX] + [
        n for finger in FINGERS[1:] for n in [finger, *FLEX]]
    assert [m.type_name for m in hand.get_motors()][:6] == [
        "MotorZ", "MotorX", "MotorY", "MotorZ", "MotorZ", "MotorZ"]


def test_hand_parts_are_the_manuals_classes_and_files(scene):
    round_parts = [type(p) for p in RoundHand(scene, "r").get_parts() if not p.type_name.startswith("Motor")]
    assert round_parts == [RoundPalm] + [RoundFinger] * 15
    anthro = [p for p in AnthroHand(scene, "a").get_parts() if not p.type_name.startswith("Motor")]
    assert [type(p) for p in anthro[:3]] == [AnthroPalm, AnthroThumb, RoundFinger]
    assert [p.mesh.url.rsplit("/", 1)[1] for p in anthro[2:5]] == [
        "round-finger-8.glb", "round-finger-5.glb", "round-tip.glb"]


@pytest.mark.parametrize("kind, spread, flex", [
    (RoundHand, lambda i: 4 * i, lambda i: [4 * i + 1, 4 * i + 2, 4 * i + 3]),
    (AnthroHand, lambda i: 1 if i == 0 else 4 * i + 2, lambda i: [4 * i + 3, 4 * i + 4, 4 * i + 5]),
])
def test_each_method_moves_exactly_the_motors_the_spec_names(scene, kind, spread, flex):
    for finger in range(5):
        hand = kind(scene, f"h{finger}")
        before = hand.get_angles()
        hand.flex_finger(finger, 0.3)
        moved = [i for i, (a, b) in enumerate(zip(before, hand.get_angles())) if a != b]
        assert moved == flex(finger) and all(hand.get_angles()[i] == -0.3 for i in moved)
        before = hand.get_angles()
        hand.spread_finger(finger, -0.1)  # within every spread motor's range (thumb: 0…π/2)
        moved = [i for i, (a, b) in enumerate(zip(before, hand.get_angles())) if a != b]
        assert moved == [spread(finger)]


@pytest.mark.parametrize("kind, thumb", [(RoundHand, lambda a: -3 * a), (AnthroHand, lambda a: 0.5 - 2 * a)])
def test_spread_fingers_includes_the_thumb_as_the_spec_says(scene, kind, thumb):
    hand = kind(scene, "h")
    motors = hand.get_motors()
    hand.spread_fingers(0.2, True)
    thumb_motor = motors[hand.spread_index(0)]
    expected = max(thumb_motor.min, min(thumb_motor.max, -thumb(0.2)))
    assert thumb_motor.get_angle() == pytest.approx(expected)
    assert [motors[hand.spread_index(i)].get_angle() for i in range(1, 5)] == pytest.approx(
        [-0.2, -0.06, 0.06, 0.2])


def test_round_hands_are_recoloured_grey_and_right_ones_mirrored(scene):
    left, right = RoundHand(scene, "l", True), RoundHand(scene, "r", False)
    palm = left.get_parts()[0]
    assert palm.describe()["recolors"] == [[[0.0, 0.21, 1.0], [0.3, 0.3, 0.3], 0.01]]
    assert palm.geometry()["mirror"] is False and right.get_parts()[0].geometry()["mirror"] is True
    assert palm.geometry()["offset"] == [0.0, 0.7, 0.0]


def test_mesh_envelopes_are_a_few_dozen_hull_points_and_mirror_with_the_part(scene):
    left, right = RoundPalm(scene, "l", True, "round-palm.glb"), RoundPalm(scene, "r", False, "round-palm.glb")
    points = left.geometry()["points"]
    assert 20 <= len(points) <= 80
    mirrored = sorted((-x, y, z) for x, y, z in right.geometry()["points"])
    assert [c for p in mirrored for c in p] == pytest.approx(
        [c for p in sorted(tuple(p) for p in points) for c in p])
    ys = [p[1] for p in points]  # the file's box raised by length/2
    assert min(ys) == pytest.approx(-0.864 + 0.7, abs=0.02)
    clearance = [-max(sum((p[k] - position[k]) * u[k] for k in range(3)) for p in points)
                 for position, rotation, order in round_palm_slots(True, 1.4)[1:]
                 for u in [slot_direction(rotation, order)]]
    assert min(clearance) == pytest.approx(PALM_JOINT_GAP)  # the lowest finger's, exactly


def _touching_within(scene, hand):
    """Pairs of the hand's own parts that touch (sorted ids)."""
    parts = {p.id for p in hand.get_parts() if p.physical}
    return {tuple(sorted((a, b))) for a in parts for b in scene.bodies.touching(scene.get(a)) if b in parts}


@pytest.mark.parametrize("kind", [RoundHand, AnthroHand])
@pytest.mark.parametrize("left", [True, False])
def test_hands_at_rest_and_spread_open_touch_nothing_of_their_own(scene, kind, left):
    hand = kind(scene, "h", left)
    assert _touching_within(scene, hand) == set()
    hand.flex_fingers(0)
    hand.spread_fingers(1, True)
    assert _touching_within(scene, hand) == set()


def _physical_neighbours(motor):
    below, above = motor.parent, next(iter(motor.children), None)
    while below is not None and not below.physical:
        below = below.parent
    while above is not None and not above.physical:
        above = next(iter(above.children), None)
    return below, above


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


@pytest.mark.parametrize("length", [0.001, 0.01, 0.05, 3.0, 1000.0])
def test_round_fingers_of_any_length_get_an_envelope_when_made(scene, length):
    finger = RoundFinger(scene, "f", "round-finger-8.glb", length)
    points = finger.geometry()["points"]
    assert len(points) >= 4
    finger.set_position((0, 5, 0))
    scene.tick(0.1)  # the tick describes the new part: nothing is left to fail there
    assert scene.failures == 0
