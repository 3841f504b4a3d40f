"""Edged parts, shapes and slots: the figures of spec/parts.md."""

import math

import pytest

from server.core.kit import math3d
from server.core.model.node import Slot
from server.core.model.parts import Ball, Box, EdgedFinger, EdgedPalm, EdgedTip, Part
from server.core.model.robot import Robot
from server.core.kit.errors import Cycle


def flat(points):
    return [c for p in points for c in p]


def test_edged_finger_profile_and_slot(scene):
    finger = EdgedFinger(scene, "f", 2, 0.4, 0.2)
    t, i, e = 0.1, 0.2 / 8, 0.003
    profile = [(-t, i), (-t + i, e), (0, e), (t, t), (t, 2 - t - e), (0, 2 - e),
               (-t + i, 2 - e), (-t, 2 - i)]
    assert flat(p[:2] for p in finger.points[:8]) == pytest.approx(flat(profile))
    assert sorted({p[2] for p in finger.points}) == pytest.approx([-0.2, 0.2])
    assert len(finger.points) == 16
    assert [s.position for s in finger.slots] == [(0.0, 2.0, 0.0)]


def test_edged_tip_has_a_different_top_and_a_slot(scene):
    tip = EdgedTip(scene, "t", 1)
    i, e = 0.3 / 8, 0.003
    assert tip.points[4][:2] == pytest.approx((0.15, 1 - i - e))
    assert tip.points[5][:2] == pytest.approx((0.15 - i, 1 - e))
    assert len(tip.slots) == 1


@pytest.mark.parametrize("left", [True, False])
def test_edged_palm_slots_lie_on_the_profile_edges(scene, left):
    palm = EdgedPalm(scene, "p", left)
    s, w, i, length = (1 if left else -1), 0.7, 1.4 / 8, 1.4
    p2, p3, p4 = (s * w, 2 * i), (s * w, length), (-s * w, length)
    expected = [(p2[0], p2[1] * 0.75 + p3[1] * 0.25)] + [
        (p3[0] * (1 - k) + p4[0] * k, length) for k in (1 / 8, 3 / 8, 5 / 8, 7 / 8)]
    assert flat(slot.position[:2] for slot in palm.slots) == pytest.approx(flat(expected))


def test_edged_palm_finger_slots_point_up_and_thumb_slot_points_sideways(scene):
    left, right = EdgedPalm(scene, "l", True), EdgedPalm(scene, "r", False)
    up = (0, 1, 0)
    for palm in (left, right):
        for slot in palm.slots[1:]:
            assert math3d.rotate(slot.world_pose()[1], up) == pytest.approx((0, 1, 0), abs=1e-9)
    # The thumb slot's +Y points out of the palm's side: +X for a left palm, -X for a right.
    assert math3d.rotate(left.slots[0].world_pose()[1], up) == pytest.approx((1, 0, 0), abs=1e-9)
    assert math3d.rotate(right.slots[0].world_pose()[1], up) == pytest.approx((-1, 0, 0), abs=1e-9)


def test_shapes_have_no_slots_and_exact_geometry(scene):
    ball, box = Ball(scene, "b", 2, "red"), Box(scene, "x", 2, 1, 3)
    assert ball.geometry() == {"kind": "sphere", "radius": 2, "color": "red"}
    assert box.geometry() == {"kind": "box", "size": [2, 1, 3], "color": "dimgray"}
    assert ball.slots == box.slots == []


def test_attach_to_slot_by_index_object_and_parent_without_slots(scene):
    palm, box = EdgedPalm(scene, "p", True), Box(scene, "b")
    a, b, c = Part(scene, "a"), Part(scene, "b2"), Part(scene, "c")
    a.attach_to_slot(palm, 2)
    assert a.parent is palm.slots[2]
    custom = Slot(scene, "s", (0, 3, 0))
    b.attach_to_slot(palm, custom)
    # the slot is palm's child, not one of its slots: indices keep their meaning
    assert b.parent is custom and custom.parent is palm and len(palm.slots) == 5
    assert custom not in palm.slots
    c.attach_to_slot(box)
    assert c.parent is box


def test_a_slot_object_moved_to_another_parent_leaves_its_old_slot_list(scene):
    first, second, part = EdgedFinger(scene, "f1"), EdgedFinger(scene, "f2"), Part(scene, "a")
    extra = first.add_slot((0, 0.5, 0))
    part.attach_to_slot(second, extra)
    assert extra.parent is second and extra not in first.slots and extra not in second.slots
    again = Part(scene, "b")
    again.attach_to_slot(second, extra)  # already a child of second: stays as it is
    assert again.parent is extra and extra.parent is second


@pytest.mark.parametrize("index", [5, 17, -1])
def test_a_missing_slot_index_attaches_to_the_parent_itself_with_a_warning(scene, index):
    palm, part = EdgedPalm(scene, "p", True), Part(scene, "a")
    with scene.recording() as changes:
        part.attach_to_slot(palm, index)
    assert part.parent is palm
    [warning] = changes.warnings
    assert "p has 5 slots and no slot" in warning and "attached to p itself" in warning


def test_attaching_to_a_part_without_slots_warns_only_for_an_index_other_than_0(scene):
    robot, box = Robot(scene, "r"), Box(scene, "b")
    with scene.recording() as changes:
        Part(scene, "a").attach_to_slot(robot)
        Part(scene, "c").attach_to_slot(box, 0)
    assert changes.warnings == []
    with scene.recording() as changes:
        Part(scene, "d").attach_to_slot(box, 1)
    assert changes.warnings == ["b has 0 slots and no slot 1: d is attached to b itself, as 1.0 does"]


def test_attaching_below_itself_is_a_cycle(scene):
    first, second = EdgedFinger(scene, "f1"), EdgedFinger(scene, "f2")
    second.attach_to_slot(first)
    with pytest.raises(Cycle):
        first.attach_to_slot(second)
    with pytest.raises(Cycle):
        first.attach_to_slot(first)
    assert second.parent is first.slots[0] and first.parent is None


def test_add_slot_and_rotated_slot_orients_attached_part(scene):
    robot, finger = Robot(scene, "r"), EdgedFinger(scene, "f", 1)
    base = Part(scene, "base")
    base.attach_to_slot(robot)
    slot = base.add_slot((1, 0, 0))
    slot.set_rotation(0, 0, -math.pi / 2)
    finger.attach_to_slot(base, 0)
    # The finger grows along the slot's +Y, which the rotation turned to +X.
    assert finger.slots[0].world_pose()[0] == pytest.approx((2, 0, 0))
