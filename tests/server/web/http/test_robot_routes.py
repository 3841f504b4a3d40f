"""Robots from files over HTTP, against a real server: a URDF zip placed in a scene comes
back as an ordinary robot (REST, frames, a Python client steering it), and every bad
upload is a 4xx naming what is wrong that makes nothing."""

from __future__ import annotations

import io
import json
import zipfile

import pytest

import virtual_prosthetics as vp
from tests import hand_files
from tests.conftest import eventually
from tests.hand_files import hand_urdf, hand_zip, zipped
from tests.server.web.http.test_assets import request


def robot_ids(server, scene):
    return [r["id"] for r in server.get(f"/api/scenes/{scene}/robots")]


def test_a_urdf_zip_placed_in_a_scene_is_a_robot_any_client_steers(server, scene_name):
    session = vp.connect(server.ws, scene_name)
    try:
        status, _, body = request(server, "POST",
                                  f"/api/scenes/{scene_name}/robots?position=0,0.3,0.1", hand_zip())
        robot = json.loads(body)
        assert status == 201, body
        assert (robot["id"], robot["name"], robot["owner"], robot["shared"]) == \
            ("api.1", "test_hand", "api", True)
        assert [(m["name"], m["min"], m["max"]) for m in robot["motors"]] == \
            [(name, *hand_files.LIMITS) for name in hand_files.motor_names()]
        assert robot["motors"][1]["follows"] == [robot["motors"][0]["id"], *hand_files.MIMIC]
        assert robot["position"] == [0.0, 0.3, 0.1]
        assert {p["name"] for p in robot["parts"]} >= {"palm", "camera_mount", "index_distal"}
        eventually(lambda: session.read(lambda mirror: robot["id"] in mirror.nodes))
        hand = session.proxy(robot["id"])  # shared: another client steers it
        hand.set_angles(1.0)
        session.sync()
        ratio, offset = hand_files.MIMIC
        assert hand.get_angles()[:3] == pytest.approx([1.0, ratio + offset, ratio + offset])
        motors = server.get(f"/api/scenes/{scene_name}/robots/api.1")["motors"]
        assert [m["angle"] for m in motors[:3]] == pytest.approx([1.0, ratio + offset, ratio + offset])
        for form, description in (("urdf", "robot.urdf"), ("mjcf", "robot.xml")):  # names kept
            status, headers, data = request(server, "GET", f"/api/scenes/{scene_name}/robots/api.1/{form}")
            with zipfile.ZipFile(io.BytesIO(data)) as archive:
                text = archive.read(f"api.1/{description}").decode()
            assert status == 200 and 'name="index_middle_joint"' in text, form
            assert ('<mimic joint="index_proximal_joint"' in text) == (form == "urdf")
    finally:
        session.close()


def test_bad_robot_uploads_are_refused_naming_what_is_wrong_and_make_nothing(server, scene_name):
    vp.connect(server.ws, scene_name).close()
    path = f"/api/scenes/{scene_name}/robots"
    cases = [
        (b"not a robot", 400, "neither a zip nor a URDF"),
        (zipped({"h.urdf": hand_urdf("../../../../etc/passwd")}), 403, "leaves the upload"),
        (zipped({"a.urdf": hand_urdf(), "b.urdf": hand_urdf()}), 400, "name one with ?file="),
        (hand_urdf().encode(), 400, "is not in the upload"),
        (hand_urdf("tip.stl", '<link name="x"/><joint name="loose" type="floating"><parent link="palm"/>'
                   '<child link="x"/></joint>').encode(),
         400, "joint 'loose' is floating"),
    ]
    for body, status, words in cases:
        answer, _, text = request(server, "POST", path, body)
        refusal = json.loads(text)
        assert answer == status and words in refusal["message"], (answer, refusal)
    answer, _, text = request(server, "POST", f"{path}?position=1,2", hand_zip())
    assert answer == 400 and "?position= takes 3 finite numbers" in json.loads(text)["message"]
    answer, _, _ = request(server, "POST", "/api/scenes/no-such-scene/robots", hand_zip())
    assert answer == 404
    assert robot_ids(server, scene_name) == []


def test_an_mjcf_zip_is_placed_as_mujoco_compiles_it_and_runs_in_dynamic_mode(server, scene_name):
    session = vp.connect(server.ws, scene_name)
    try:
        vp.set_physics("dynamic", unit=1.0)  # a scene unit a metre: the hand 0.4 m up
        status, _, body = request(server, "POST", f"/api/scenes/{scene_name}/robots?position=0,0.4,0",
                                  hand_files.mjcf_zip())
        robot = json.loads(body)
        assert status == 201, body
        assert robot["name"] == "mjcf_hand" and len(robot["motors"]) == 10
        named = {m["name"]: m for m in robot["motors"]}
        assert named["index_distal_joint"]["follows"][0] == named["index_middle_joint"]["id"]
        eventually(lambda: session.read(lambda mirror: robot["id"] in mirror.nodes))
        hand = session.proxy(robot["id"])
        curling = [m["follows"] is None and not m["name"].startswith(("thumb", "middle_spread"))
                   for m in robot["motors"]]  # the thumb would cross the index: it stays open
        hand.set_angles(*[0.8 if curls else None for curls in curling])

        def curled():
            angles = [m["angle"] for m in server.get(f"/api/scenes/{scene_name}/robots/{robot['id']}")["motors"]]
            return all(abs(a - 0.8) < 0.05 for a, curls in zip(angles, curling) if curls)
        eventually(curled)  # driven by its motors under gravity, its palm held where it was put
        palm = server.get(f"/api/scenes/{scene_name}/robots/{robot['id']}")["parts"][0]
        assert palm["world"]["position"] == pytest.approx([0.0, 0.4, 0.0], abs=1e-3)
    finally:
        session.close()
