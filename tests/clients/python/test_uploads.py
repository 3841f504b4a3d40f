"""Uploading mesh files from Python: an uploaded GLB makes parts in any scene; what is not a mesh is refused."""

from __future__ import annotations

import math

import pytest
import trimesh

import virtual_prosthetics as vp


def test_an_uploaded_glb_makes_gltf_parts_in_any_scene(server, scene, scene_name, tmp_path):
    ball = trimesh.creation.icosphere(2, 0.4)
    path = tmp_path / "ball.glb"
    path.write_bytes(ball.export(file_type="glb"))
    name = vp.upload_asset(path)
    assert vp.upload_asset(path.read_bytes()) == name  # the same bytes, the same name
    decoration = vp.GLTFPart(name, 0.8, callback=lambda p: None)
    finger = vp.RoundFinger(name, 0.8, callback=lambda p: None)  # physical: an envelope
    finger.set_position(3, 1, 0)
    sensor = vp.Sensor()
    sensor.set_position(3, 3, 0)
    sensor.set_rotation(math.pi, 0, 0)
    nodes = {n["id"]: n for n in server.nodes(scene_name)}
    assert nodes[decoration.id]["geometry"]["url"] == f"/api/assets/{name}"
    assert 20 <= len(nodes[finger.id]["geometry"]["points"]) <= 80
    top = 1 + 0.4 + ball.vertices[:, 1].max()  # the mesh is raised by length/2 = 0.4
    assert sensor.sense_distance() == pytest.approx(3 - top, abs=1e-6)


def test_uploads_that_are_not_meshes_are_refused_with_the_reason(scene):
    with pytest.raises(vp.ServerError) as caught:
        vp.upload_asset(b"just some bytes")
    assert caught.value.code == "bad_asset" and "neither GLB nor glTF" in caught.value.message


def test_load_robot_takes_a_folder_a_zip_or_a_file_and_the_robot_is_this_clients(server, scene, scene_name, tmp_path):
    import io
    import zipfile
    from tests import hand_files
    folder = tmp_path / "handpkg"
    with zipfile.ZipFile(io.BytesIO(hand_files.hand_zip())) as archive:
        archive.extractall(tmp_path)
    hand = vp.load_robot(folder, position=[0.5, 0.2, 0], rotation=[0, math.pi / 2, 0])
    assert isinstance(hand, vp.ImportedRobot) and hand.id.startswith(scene.client_id)
    assert hand.get_position() == [0.5, 0.2, 0.0]
    assert len(hand.get_motors()) == len(hand_files.motor_names())
    hand.get_motors()[3].set_angle(1.2)  # index proximal: its middle and distal follow
    ratio, offset = hand_files.MIMIC
    follower = min(hand_files.LIMITS[1], ratio * 1.2 + offset)
    assert hand.get_angles()[3:6] == pytest.approx([1.2, follower, follower])
    report = server.get(f"/api/scenes/{scene_name}/robots/{hand.id}")
    assert [m["name"] for m in report["motors"]] == hand_files.motor_names()
    zipped = tmp_path / "hand.zip"
    zipped.write_bytes(hand_files.hand_zip())
    assert len(vp.load_robot(zipped).get_parts()) == len(hand.get_parts())
    with pytest.raises(vp.ServerError, match="is not in the upload") as refused:
        vp.load_robot(folder / "urdf" / "hand.urdf")  # its mesh is not beside it
    assert refused.value.code == "bad_asset"
