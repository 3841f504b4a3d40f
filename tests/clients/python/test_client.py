"""The Python client against a real server: the manual's Steps 2-5, written in Python."""

from __future__ import annotations

import math
import time

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


def test_reads_see_this_clients_writes_at_once(scene):
    motor = vp.MotorX(-1, 1, 0)
    for value in (0.1, 0.2, 5, -5, None):
        motor.set_angle(value)
        expected = {0.1: 0.1, 0.2: 0.2, 5: 1, -5: -1, None: -1}[value]
        assert motor.get_angle() == expected


def test_errors_are_raised_as_server_errors(scene):
    robot = vp.Robot()
    robot.set_angles("fast")  # returns at once; the error comes with the next read
    with pytest.raises(vp.ServerError) as caught:
        robot.get_angles()
    assert caught.value.code == "wrong_type" and "setAngles" in caught.value.message
    finger = vp.EdgedFinger()
    finger.attach_to_slot(finger)
    with pytest.raises(vp.ServerError) as caught:
        scene.sync()
    assert caught.value.code == "cycle"
    assert robot.get_angles() == []  # the connection carries on


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


def test_two_clients_share_a_scene_and_viewers_cannot_change_it(server, scene, scene_name):
    hand = vp.EdgedHand(False)
    hand.flex_finger(1, 0.3)
    scene.sync()
    other = vp.Scene(server.ws, scene=scene_name, role="viewer")
    try:
        seen = other.proxy(hand.id)
        assert isinstance(seen, vp.EdgedHand)
        assert seen.get_angles() == hand.get_angles()
        hand.spread_finger(2, 0.2)
        deadline = time.monotonic() + 5
        while seen.get_angles()[8] != pytest.approx(-0.2) and time.monotonic() < deadline:
            time.sleep(0.01)
        assert seen.get_angles()[8] == pytest.approx(-0.2)
        seen.flex_fingers(1)
        with pytest.raises(vp.ServerError) as caught:
            other.sync()
        assert caught.value.code == "forbidden"
        assert hand.get_angles()[5] == pytest.approx(-0.3)
    finally:
        other.close()


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


def test_camera_and_time(server, scene, scene_name):
    vp.set_camera_position(10, 2, 0)
    vp.set_camera_target([0, 2, 0])
    scene.sync()
    assert server.get(f"/api/scenes/{scene_name}")["camera"] == {
        "position": [10, 2, 0], "target": [0, 2, 0]}
    started, first = time.monotonic(), vp.get_time()
    time.sleep(0.1)
    later, elapsed = vp.get_time(), time.monotonic() - started
    assert first < later and later - first == pytest.approx(elapsed, abs=0.1)


def test_disconnect_removes_the_clients_robots(server, scene_name):
    with vp.connect(server.ws, scene=scene_name):
        vp.EdgedHand()
        vp.current_scene().sync()
        assert server.get(f"/api/scenes/{scene_name}")["robots"] == 1
    deadline = time.monotonic() + 5
    while server.get(f"/api/scenes/{scene_name}")["robots"] and time.monotonic() < deadline:
        time.sleep(0.05)
    assert server.get(f"/api/scenes/{scene_name}")["robots"] == 0


def test_keep_leaves_a_scripts_robots_after_it_ends(server, scene_name):
    with vp.connect(server.ws, scene=scene_name, keep=True):
        vp.EdgedHand().share()
        vp.current_scene().sync()
    time.sleep(1.5)  # past the test server's grace period
    [robot] = server.get(f"/api/scenes/{scene_name}/robots")
    assert robot["type"] == "EdgedHand" and robot["shared"]


def test_run_stops_with_an_error_when_the_server_goes_away(scene_name):
    from ...conftest import eventually, start_server, stop_server
    own = start_server("--no-demo", "--limit", "leaveGraceSeconds=1")  # the client tries 1 s
    try:
        # scenes start from a fork server a fresh server is still warming (slow under load)
        eventually(lambda: [s["state"] for s in own.get("/api/scenes")] == ["running"], 60)
        vp.connect(own.ws, scene=scene_name)
        vp.set_animation(lambda t: None)
        stop_server(own)
        with pytest.raises(vp.ConnectionLost):
            vp.run(30)
    finally:
        stop_server(own)
