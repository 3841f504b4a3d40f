"""The manual's objects from Python against a real server: Steps 2-5, slots and chains, GLTF parts."""

from __future__ import annotations

import math

import pytest

import virtual_prosthetics as vp


def motor_angles(server, scene_name, robot):
    return [m["angle"] for m in server.get(f"/api/scenes/{scene_name}/robots/{robot.id}")["motors"]]


def test_step2_simple_robot(server, scene, scene_name):
    robot = vp.Robot()
    robot.attach_chain(vp.MotorZ(), vp.EdgedFinger(), vp.MotorZ(), vp.EdgedFinger(),
                       vp.MotorZ(), vp.EdgedFinger())
    motors = robot.get_motors()
    assert [type(m) for m in motors] == [vp.MotorZ] * 3
    assert [type(p).__name__ for p in robot.get_parts()] == ["MotorZ", "EdgedFinger"] * 3
    report = server.get(f"/api/scenes/{scene_name}/robots/{robot.id}")
    assert [m["id"] for m in report["motors"]] == [m.id for m in motors]


def test_step3_animation_moves_the_motors_on_the_server(server, scene, scene_name):
    robot = vp.Robot()
    robot.attach_chain(vp.MotorZ(), vp.EdgedFinger(), vp.MotorZ(), vp.EdgedFinger(),
                       vp.MotorZ(), vp.EdgedFinger())
    seen = []

    def loop(t):
        robot.set_angles(-0.7 * math.sin(t), -1.6 * (0.5 + 0.5 * math.sin(t)),
                         -1.6 * (0.5 + 0.5 * math.sin(t)))
        seen.append(t)
    vp.set_animation(loop, 30)
    vp.run(0.5)
    assert 3 <= len(seen) <= 20 and seen == sorted(seen)  # 30 a second, fewer when busy
    expected = robot.get_angles()
    t = seen[-1]
    assert expected == pytest.approx([-0.7 * math.sin(t), -1.6 * (0.5 + 0.5 * math.sin(t)),
                                      -1.6 * (0.5 + 0.5 * math.sin(t))])
    # The server holds what the script set (REST reads the live scene).
    assert motor_angles(server, scene_name, robot) == pytest.approx(expected)


def test_step4_custom_sizes_and_limits_clamp(server, scene, scene_name):
    robot = vp.Robot()
    robot.attach_chain(
        vp.MotorZ(-0.7, 0.7, 0, 0.2, 0.6), vp.EdgedFinger(1, 1, 0.1),
        vp.MotorZ(-1.6, 0, 0, 0.4, 0.3), vp.EdgedFinger(2),
        vp.MotorZ(-1.6, 0, 0, 0.4, 0.2), vp.EdgedFinger(0.7, 0.1))
    robot.set_angles(5, 5, -5)
    assert robot.get_angles() == [0.7, 0, -1.6]
    assert motor_angles(server, scene_name, robot) == [0.7, 0, -1.6]
    snapshot = server.get(f"/api/scenes/{scene_name}/snapshot")
    widths = [n["geometry"]["length"] for n in snapshot["nodes"] if n["type"] == "MotorZ"]
    assert widths == [0.2, 0.4, 0.4]


class Digger(vp.Robot):
    """The manual's Step 5 class, in Python."""

    def __init__(self, speed):
        super().__init__()
        self.speed = speed
        self.attach_chain(
            vp.MotorZ(-0.7, 0.7, 0, 0.2, 0.6), vp.EdgedFinger(1, 1, 0.1),
            vp.MotorZ(-1.6, 0, 0, 0.4, 0.3), vp.EdgedFinger(2),
            vp.MotorZ(-1.6, 0, 0, 0.4, 0.2), vp.EdgedFinger(0.7, 0.1))

    def dig(self, time):
        time = time * self.speed
        self.set_angles(-0.7 * math.sin(time + 3), -1.6 * (0.5 + 0.5 * math.sin(time + 1)),
                        -1.6 * (0.5 + 0.5 * math.sin(time)))


def test_step5_three_diggers(server, scene, scene_name):
    robot_a, robot_b, robot_c = Digger(2), Digger(3), Digger(4)
    robot_a.set_position(0, 0, 1)
    robot_c.set_position([0, 0, -1])
    vp.set_animation(lambda t, dt: [r.dig(t) for r in (robot_a, robot_b, robot_c)])
    vp.run(0.3)
    robots = server.get(f"/api/scenes/{scene_name}/robots")
    assert [r["position"] for r in robots] == [[0, 0, 1], [0, 0, 0], [0, 0, -1]]
    assert robot_a.get_position() == [0, 0, 1]
    for robot in (robot_a, robot_b, robot_c):
        assert motor_angles(server, scene_name, robot) == pytest.approx(robot.get_angles())
    assert robot_a.get_angles() != robot_c.get_angles()  # different speeds
    assert robot_a.get_motors()[0] in robot_a.get_parts()


def test_a_missing_slot_index_attaches_to_the_parent_and_warns(server, scene, scene_name):
    palm = vp.EdgedPalm()
    ball = vp.Ball(0.2)
    ball.attach_to_slot(palm, 7)
    with pytest.warns(vp.ServerWarning, match="has 5 slots and no slot 7"):
        scene.sync()
    marker = vp.Slot(0, 3, 0)
    box = vp.Box().attach_to_slot(palm, marker)
    scene.sync()
    nodes = {n["id"]: n for n in server.nodes(scene_name)}
    assert nodes[ball.id]["parent"] == palm.id and nodes[box.id]["parent"] == marker.id
    assert nodes[palm.id]["children"] == [f"{palm.id}/s{k}" for k in range(5)] + [ball.id, marker.id]


def test_gltf_part_callback_runs_once_made_and_recolor_reaches_the_scene(server, scene, scene_name):
    ready = []
    part = vp.GLTFPart("../assets/gltf/round-palm.glb", 1.4,
                       callback=lambda p: (ready.append(p), p.recolor([0, 0.21, 1], "red")))
    assert ready == [part]
    scene.sync()
    node = next(n for n in server.nodes(scene_name)
                if n["id"] == part.id)
    assert node["geometry"]["url"] == "/assets/gltf/round-palm.glb"
    assert node["recolors"] == [[[0.0, 0.21, 1.0], "red", 0.01]]


@pytest.mark.parametrize("filename", ["../../etc/passwd", "/etc/passwd", "round-palm.glb/..",
                                      "http://example.com/x.glb", "..%2fetc%2fpasswd.glb",
                                      "assets\\gltf\\round-palm.glb", "round-palm.glb\n"])
def test_forbidden_filenames_are_refused_and_nothing_is_made(server, scene, scene_name, filename):
    before = server.nodes(scene_name)
    with pytest.raises(vp.ServerError) as caught:
        vp.GLTFPart(filename, callback=lambda p: None)
    assert caught.value.code in ("forbidden", "bad_message")
    assert server.nodes(scene_name) == before


def test_a_missing_mesh_file_is_an_unknown_asset(scene):
    with pytest.raises(vp.ServerError) as caught:
        vp.RoundFinger("no-such-finger.glb", callback=lambda p: None)
    assert caught.value.code == "unknown_asset" and "round-palm.glb" in caught.value.message


def test_round_hand_parts_are_the_manuals_classes(scene):
    hand = vp.AnthroHand(False)
    scene.sync()
    parts = [type(p) for p in hand.get_parts() if not isinstance(p, vp.Motor)]
    assert parts[:3] == [vp.AnthroPalm, vp.AnthroThumb, vp.RoundFinger]
    assert len(hand.get_motors()) == 22 and len(vp.RoundHand().get_motors()) == 20
