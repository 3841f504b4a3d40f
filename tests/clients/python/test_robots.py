"""Robots and hands from Python: their parts and motors come back as the manual's classes."""

from __future__ import annotations

import virtual_prosthetics as vp


def test_hand_parts_come_back_as_typed_objects(scene):
    hand = vp.EdgedHand()
    parts = hand.get_parts()
    assert type(parts[0]) is vp.EdgedPalm
    assert [type(m) for m in hand.get_motors()[:4]] == [vp.MotorX, vp.MotorZ, vp.MotorZ, vp.MotorZ]
    slot = parts[0].add_slot(0, 3, 0)
    assert isinstance(slot, vp.Slot)
    ball = vp.Ball(0.2, "red")
    ball.attach_to_slot(parts[0], slot)
    assert ball in hand.get_parts()


def test_a_hand_is_built_by_chained_calls_as_in_1_0(scene):
    hand = vp.EdgedHand(True).set_position(-2, 0.5, 0).set_rotation(-1, -1, 0)
    assert isinstance(hand, vp.EdgedHand)
    scene.sync()
    assert hand.get_position() == [-2, 0.5, 0]
