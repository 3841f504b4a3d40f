"""A session from Python: reads that see its own writes, other sessions of the scene, what stays when it ends."""

from __future__ import annotations

import time

import pytest

import virtual_prosthetics as vp


def test_reads_see_this_clients_writes_at_once(scene):
    motor = vp.MotorX(-1, 1, 0)
    for value in (0.1, 0.2, 5, -5, None):
        motor.set_angle(value)
        expected = {0.1: 0.1, 0.2: 0.2, 5: 1, -5: -1, None: -1}[value]
        assert motor.get_angle() == expected


def test_two_clients_share_a_scene_and_viewers_cannot_change_it(server, scene, scene_name):
    hand = vp.EdgedHand(False)
    hand.flex_finger(1, 0.3)
    scene.sync()
    other = vp.Scene(server.ws, scene=scene_name, role="viewer")  # its 0.x name still works
    try:
        assert isinstance(other, vp.Session) and vp.current_scene() is scene
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
        vp.current_session().sync()
        assert server.get(f"/api/scenes/{scene_name}")["robots"] == 1
    deadline = time.monotonic() + 5
    while server.get(f"/api/scenes/{scene_name}")["robots"] and time.monotonic() < deadline:
        time.sleep(0.05)
    assert server.get(f"/api/scenes/{scene_name}")["robots"] == 0


def test_keep_leaves_a_scripts_robots_after_it_ends(server, scene_name):
    with vp.connect(server.ws, scene=scene_name, keep=True):
        vp.EdgedHand().share()
        vp.current_session().sync()
    time.sleep(1.5)  # past the test server's grace period
    [robot] = server.get(f"/api/scenes/{scene_name}/robots")
    assert robot["type"] == "EdgedHand" and robot["shared"]
