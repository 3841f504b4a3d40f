"""The three hands: their chains, motor names and order, and what each finger method moves."""

import math

import pytest

from server.core.model.hands import AnthroHand, EdgedHand, RoundHand
from server.core.kit.errors import OutOfRange

FINGERS = ["Thumb", "Index finger", "Middle finger", "Ring finger", "Little finger"]
FLEX = ["proximal", "middle", "distal"]


def test_edged_hand_has_twenty_motors_in_finger_order(scene):
    hand = EdgedHand(scene, "h", True)
    motors = hand.get_motors()
    assert [m.type_name for m in motors] == ["MotorX", "MotorZ", "MotorZ", "MotorZ"] * 5
    assert [m.min for m in motors[0::4]] == [-1, -0.4, -0.4, -0.4, -0.4]
    assert all(m.angle == pytest.approx(-math.pi / 4) for i, m in enumerate(motors) if i % 4)
    # every finger hangs on its own palm slot, thumb first
    assert [motors[4 * i].parent for i in range(5)] == hand.palm.slots


def test_edged_hand_parts_and_sizes(scene):
    hand = EdgedHand(scene, "h")
    types = [p.type_name for p in hand.get_parts()]
    assert types.count("EdgedFinger") == 10 and types.count("EdgedTip") == 5
    first_segments = [p for p in hand.get_parts() if p.type_name == "EdgedFinger"][0::2]
    assert [f.length for f in first_segments] == [1, 1, 1.1, 1, 0.8]


def test_left_hand_flips_spread_motors_right_hand_does_not(scene):
    left, right = EdgedHand(scene, "l", True), EdgedHand(scene, "r", False)
    assert all(m.flipped for m in left.get_motors()[0::4])
    assert not any(m.flipped for m in right.get_motors()[0::4])


def test_flex_and_spread_set_the_right_motors(scene):
    hand = EdgedHand(scene, "h")
    hand.flex_finger(1, 0.5)
    hand.spread_finger(3, 0.1)
    angles = hand.get_angles()
    assert angles[5:8] == [-0.5] * 3
    assert angles[12] == pytest.approx(-0.1)
    assert angles[1] == pytest.approx(-math.pi / 4)  # thumb untouched
    hand.flex_fingers(0.3)
    assert all(a == pytest.approx(-0.3) for i, a in enumerate(hand.get_angles()) if i % 4)


def test_spread_fingers_with_and_without_thumb(scene):
    hand = EdgedHand(scene, "h")
    hand.spread_fingers(0.2)
    assert hand.get_angles()[0::4] == pytest.approx([0, -0.2, -0.06, 0.06, 0.2])
    hand.spread_fingers(0.2, True)
    assert hand.get_angles()[0] == pytest.approx(-(-1 + 3 * 0.2))


def test_finger_index_out_of_range(scene):
    hand = EdgedHand(scene, "h")
    with pytest.raises(OutOfRange):
        hand.flex_finger(5, 0.1)


def test_open_hand_fingertips_are_above_the_palm(scene):
    hand = EdgedHand(scene, "h")
    hand.flex_fingers(0)
    tips = [p for p in hand.get_parts() if p.type_name == "EdgedTip"]
    heights = [tip.slots[0].world_pose()[0][1] for tip in tips[1:]]
    # palm 1.4 + spread motor + size + 0.5 + 0.5 (the thumb points sideways)
    assert heights == pytest.approx([1.4 + s + 1.0 for s in (1, 1.1, 1, 0.8)])


def test_a_hand_at_rest_touches_nothing(scene):
    hand = EdgedHand(scene, "h", True)
    hand.set_position((0, 1, 0))
    assert scene.bodies.overlaps().pairs == frozenset()


def test_a_finger_flexed_into_its_palm_touches_it_and_stops_on_unflexing(scene):
    hand = EdgedHand(scene, "h", True)
    hand.set_position((0, 1, 0))
    palm, index_base = hand.get_parts()[0], hand.get_parts()[10]
    assert (palm.type_name, index_base.type_name) == ("EdgedPalm", "EdgedFinger")
    hand.flex_finger(1, 1.2)
    assert scene.bodies.overlaps().pairs == {(palm.id, index_base.id)}
    hand.flex_finger(1, 0)  # straight again: Bullet's cached contact points must not linger
    assert scene.bodies.overlaps().pairs == frozenset()
    hand.flex_finger(0, 1.5)
    assert scene.bodies.touching(palm) == [hand.get_parts()[3].id]  # the thumb's base


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


def test_finger_methods_leave_alone_motors_the_hand_no_longer_has(scene):
    """A finger taken off (attached to another robot, or deleted) no longer follows the
    hand's finger methods; when taking it off is undone, it follows again."""
    from server.core.model.robot import Robot

    hand, other = EdgedHand(scene, "h"), Robot(scene, "o")
    motors = hand.get_motors()
    hand.flex_fingers(0.3)
    with pytest.raises(RuntimeError), scene.journal.transaction():
        other.attach_chain(motors[8])  # the middle finger, then undone
        hand.flex_fingers(0.4)
        raise RuntimeError
    hand.flex_fingers(0.5)
    assert [m.angle for m in motors[9:12]] == [pytest.approx(-0.5)] * 3
    with scene.journal.transaction():
        other.attach_chain(motors[8])
    hand.flex_fingers(0.6)
    assert [m.angle for m in motors[9:12]] == [pytest.approx(-0.5)] * 3  # left alone
    assert motors[5].angle == pytest.approx(-0.6)
    with scene.journal.transaction():
        scene.delete(motors[12])  # the ring finger
    hand.flex_fingers(0.7)
    assert motors[1].angle == pytest.approx(-0.7) and motors[13].angle == pytest.approx(-0.6)
