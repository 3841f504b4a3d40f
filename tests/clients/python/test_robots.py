"""Robots and hands from Python: their parts and motors come back as the manual's classes."""

from __future__ import annotations

import xml.etree.ElementTree as ET
import zipfile

import pytest
import trimesh

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


def test_a_hands_grip_map_names_its_motors_by_id_and_index(scene):
    hand = vp.EdgedHand(True)
    found = hand.get_grip_map()
    motors = hand.get_motors()
    thumb, *fingers = found["digits"]
    assert thumb["opposes"] and not any(finger["opposes"] for finger in fingers)
    assert [m["index"] for m in thumb["motors"]] == [1, 2, 3]  # flexFinger(0, a)'s motors
    assert [m["motor"] for m in thumb["motors"]] == [motors[i].id for i in (1, 2, 3)]
    assert [(m["index"], m["closed"]) for m in thumb["preshape"]] == [(0, -1.0)]


def test_a_hand_is_built_by_chained_calls_as_in_1_0(scene):
    hand = vp.EdgedHand(True).set_position(-2, 0.5, 0).set_rotation(-1, -1, 0)
    assert isinstance(hand, vp.EdgedHand)
    scene.sync()
    assert hand.get_position() == [-2, 0.5, 0]


def test_a_robot_exports_to_urdf_and_glb_files(scene, tmp_path):
    hand = vp.RoundHand(True).set_position(0, 2, 0)
    hand.flex_fingers(0.5)  # made and moved just now: the files show it
    urdf = hand.export_urdf(tmp_path / "hand.zip")
    with zipfile.ZipFile(urdf) as archive:
        robot = ET.fromstring(archive.read(f"{hand.id}/robot.urdf"))
        assert all(f"{hand.id}/{m.get('filename')}" in archive.namelist()
                   for m in robot.iter("mesh"))
    joints = [j.get("name") for j in robot.findall("joint") if j.get("type") != "fixed"]
    assert len(joints) == len(hand.get_motors()) == 20  # named as the motors are
    assert joints[:5] == ["Thumb", "Thumb proximal", "Thumb middle", "Thumb distal", "Index finger"]
    look = trimesh.load(hand.export_glb(tmp_path / "hand.glb"))
    metres = vp.get_physics()["unit"]  # files are in metres
    assert len(look.geometry) == 16 and look.bounds[0][1] > 0.5 * metres  # the palm and 15 segments, raised


def test_a_file_of_a_robot_deleted_is_refused_by_name(scene, tmp_path):
    hand = vp.EdgedHand()
    hand.delete()
    with pytest.raises(vp.ServerError) as refused:
        hand.export_glb(tmp_path / "x.glb")
    assert refused.value.code == "unknown_object" and hand.id in refused.value.message
    assert not (tmp_path / "x.glb").exists()
