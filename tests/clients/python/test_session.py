"""A session from Python: reads that see its own writes, other sessions of the scene, what stays when it ends."""

from __future__ import annotations

import math
import time

import pytest

import virtual_prosthetics as vp
from tests.conftest import WAIT_SECONDS


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
        deadline = time.monotonic() + WAIT_SECONDS
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
    deadline = time.monotonic() + WAIT_SECONDS
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


def _eventually(check, seconds=5.0):
    deadline = time.monotonic() + seconds
    while not check():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.02)


def test_the_physics_read_right_after_it_was_set_is_what_was_set(scene):
    """Found: ``get_physics()`` right after ``set_physics()`` gave the old mode and gravity."""
    vp.set_physics("dynamic", gravity=3.5, solver_iterations=70)
    assert vp.get_physics()["mode"] == "dynamic" and vp.get_physics()["gravity"] == 3.5
    vp.set_physics("kinematic")
    assert vp.get_physics()["mode"] == "kinematic"


def _motor_on_robot() -> tuple[vp.Robot, vp.MotorZ]:
    robot, motor = vp.Robot(), vp.MotorZ(-1, 1)
    robot.attach_chain(motor, vp.EdgedFinger())
    return robot, motor


# read kind: (write, read, expected), each on a fresh robot with one motor
READS_AFTER_WRITES = {
    "angle": (lambda r, m: m.set_angle(5), lambda r, m: m.get_angle(), 1),
    "angles": (lambda r, m: r.set_angles(-0.25), lambda r, m: r.get_angles(), [-0.25]),
    "name": (lambda r, m: m.set_name("Index"), lambda r, m: m.get_name(), "Index"),
    "max torque": (lambda r, m: m.set_max_torque(0.4), lambda r, m: m.get_max_torque(), 0.4),
    "max speed": (lambda r, m: m.set_max_speed(2.5), lambda r, m: m.get_max_speed(), 2.5),
    "no speed limit": (lambda r, m: m.set_max_speed(math.inf), lambda r, m: m.get_max_speed(),
                       math.inf),
    "position": (lambda r, m: r.set_position(1, 2, 3), lambda r, m: r.get_position(),
                 [1, 2, 3]),
    "motors": (lambda r, m: r.attach_chain(vp.MotorX()), lambda r, m: len(r.get_motors()), 2),
    "mass": (lambda r, m: m.set_mass(0.25), lambda r, m: m.get_mass(), 0.25),
    "physics": (lambda r, m: vp.set_physics("dynamic", gravity=3),
                lambda r, m: (vp.get_physics()["mode"], vp.get_physics()["gravity"]),
                ("dynamic", 3)),
}


@pytest.mark.parametrize("kind", READS_AFTER_WRITES)
def test_every_read_kind_answers_the_write_just_before_it(scene, kind):
    write, read, expected = READS_AFTER_WRITES[kind]
    robot, motor = _motor_on_robot()
    write(robot, motor)
    assert read(robot, motor) == expected


def test_a_script_switches_the_scene_to_dynamic_and_things_fall_and_are_felt(scene):
    pad = vp.Box(2, 0.2, 2).set_static()
    sensor = vp.Sensor().watch()
    sensor.attach_to_slot(pad)
    pad.set_position(0, 0.1, 0)
    load = vp.Ball(0.3).set_mass(10)
    load.set_position(0, 2, 0)
    assert load.get_mass() == 10
    vp.set_physics("dynamic", gravity=9.81, solver_iterations=60)
    scene.sync()
    assert vp.get_physics()["mode"] == "dynamic" and vp.get_physics()["solverIterations"] == 60
    _eventually(lambda: load._state()["position"][1] < 0.5)  # fallen onto the pad
    _eventually(lambda: sensor.sense_force() == pytest.approx(98.1, rel=0.05))
    assert scene.mirror.forces[load.id] == pytest.approx(98.1, rel=0.05)
    # who presses how: the ball alone, from the frames and asked of the server
    assert sensor.sense_force(load) == pytest.approx(98.1, rel=0.05)
    assert sensor.sense_force("ground") == 0.0 == sensor.sense_force("ground", exact=True)
    assert sensor.sense_force(load, exact=True) == pytest.approx(98.1, rel=0.05)
    for exact in (False, True):
        [pressing] = sensor.sense_contacts(exact=exact)
        assert pressing["other"] is load and pressing["friction"] < 1


def test_in_dynamic_mode_a_motor_reads_where_it_is_not_where_it_was_sent(scene):
    arm = vp.Robot()
    motor = vp.MotorZ().set_max_torque(1e-5)  # N·m: far too weak for the finger
    arm.attach_chain(motor, vp.EdgedFinger(2))
    arm.set_position(0, 3, 0)
    vp.set_physics("dynamic")
    motor.set_angle(-1.5)
    assert motor.get_max_torque() == 1e-5
    motor.set_max_torque(2e-5)  # a change after it was made reaches the mirror too
    scene.sync()
    assert motor.get_max_torque() == 2e-5
    time.sleep(1.0)
    scene.sync()
    assert motor.get_angle() != pytest.approx(-1.5, abs=0.2)  # the finger hangs down instead
    assert abs(motor.get_torque()) == pytest.approx(2e-5, rel=0.05)  # straining at its bound
    [torque] = arm.get_torques()  # the robot's, in motor order
    assert abs(torque) == pytest.approx(2e-5, rel=0.05)
    assert len(arm.get_speeds()) == 1 and math.isfinite(motor.get_speed())  # it swings
    assert motor.get_max_speed() == math.inf
    motor.set_max_speed(0.5)
    scene.sync()
    assert motor.get_max_speed() == 0.5
    with pytest.raises(vp.ServerError) as refused:
        motor.set_max_speed(0)
        scene.sync()
    assert refused.value.code == "out_of_range" and "speed" in str(refused.value)
    with pytest.raises(vp.ServerError) as refused:
        vp.set_physics("dynamic", substeps=0)
        scene.sync()
    assert refused.value.code == "out_of_range" and "substeps" in str(refused.value)


def _stepped_run(server, scene_name: str) -> tuple[list[float], list[float]]:
    """A hand swept through a ball under gravity, 90 ticks stepped one by one (1.5 s of
    scene time); where the ball ends and the hand's angles. (Not the scene's time: it
    started wherever the scene's clock was, so its last bits differ between runs.)"""
    with vp.connect(server.ws, scene=scene_name) as session:
        ball = vp.Ball(0.4).set_mass(2)
        ball.set_position(0.5, 0.4, 1.5)
        hand = vp.EdgedHand(False)
        hand.set_position(0, 1.2, 0)
        with session.paused():
            vp.set_physics("dynamic")
            start = session.get_time()
            for tick in range(90):
                with session.connection.gathering():
                    hand.flex_fingers(0.02 * tick)
                    hand.set_position(0.01 * tick, 1.2, 0)
                time = session.step()
            assert time - start == pytest.approx(1.5) and session.get_time() == time
            return list(ball._state()["position"]), hand.get_angles()


def test_a_paused_scene_moves_only_when_stepped_and_the_same_way_every_run(server, scene_name):
    first = _stepped_run(server, scene_name + "a")
    second = _stepped_run(server, scene_name + "b")
    assert first == second  # exactly: the run does not depend on when messages arrived
    assert first[0] != [0.5, 0.4, 1.5]  # the ball fell and was swept


def test_a_pause_ends_when_its_client_leaves_and_stepping_a_running_scene_is_refused(
        server, scene_name):
    watcher = vp.Session(server.ws, scene=scene_name, role="viewer")
    try:
        with vp.connect(server.ws, scene=scene_name) as pauser:
            pauser.pause()
            held = pauser.read(lambda mirror: mirror.time)  # the last tick's (its answer's)
            # frames sent before the pause may still be on their way to the watcher
            _eventually(lambda: watcher.read(lambda mirror: mirror.time) == held)
            time.sleep(0.5)
            assert watcher.read(lambda mirror: mirror.time) == held  # nothing ticks
        _eventually(lambda: watcher.read(lambda mirror: mirror.time) > held + 0.5)
        with vp.connect(server.ws, scene=scene_name) as stepper:
            with pytest.raises(vp.ServerError) as refused:
                stepper.step()
            assert refused.value.code == "not_paused" and "pause()" in str(refused.value)
    finally:
        watcher.close()


def test_a_saved_state_comes_back_for_this_client_and_every_viewer(server, scene_name):
    watcher = vp.Session(server.ws, scene=scene_name, role="viewer")
    try:
        with vp.connect(server.ws, scene=scene_name) as keeper:
            ball = vp.Ball(0.5)
            ball.set_position(1, 2, 3)
            state = vp.save_state()
            ball.set_position(4, 5, 6)
            box = vp.Box()
            keeper.sync()
            vp.restore_state(state)
            assert ball._state()["position"] == [1, 2, 3]  # read at once: the mirror holds it
            assert keeper.read(lambda mirror: box.id not in mirror.nodes)
            _eventually(lambda: watcher.read(lambda mirror: mirror.nodes[ball.id]["position"]) == [1, 2, 3]
                        and box.id not in mirror_ids(watcher))
            with pytest.raises(vp.ServerError) as refused:
                watcher.restore_state(state)
            assert refused.value.code == "forbidden"
            vp.forget_state(state)
            with pytest.raises(vp.ServerError) as unknown:
                vp.restore_state(state)
            assert unknown.value.code == "unknown_object" and state in str(unknown.value)
    finally:
        watcher.close()


def mirror_ids(session: vp.Session) -> set[str]:
    return session.read(lambda mirror: set(mirror.nodes))


def test_a_step_and_the_reads_after_it_go_in_one_message(scene):
    vp.set_physics("dynamic")
    scene.pause()  # before the hand is made: it is built by the first step, not by the
    # ticks that came before the pause, however many the machine's speed let in
    hand = vp.EdgedHand(True)
    hand.set_position(0, 3, 0)
    finger = hand.get_motors()[5]
    scene.step()
    start, before = scene.get_time(), finger.get_angle()
    texts = []
    sent = scene.connection._ws.send
    scene.connection._ws.send = lambda text: (texts.append(text), sent(text))[1]
    try:
        with scene.connection.gathering():
            hand.flex_fingers(1.2)  # the fingers closing
            time, angle, torques = scene.step_reading(
                [("scene", "getTime"), (finger.id, "getAngle"), (hand.id, "getTorques")], 2)
    finally:
        scene.connection._ws.send = sent
    assert len(texts) == 1  # the finger command, the step and the reads
    assert time == pytest.approx(start + 2 / 60) == scene.get_time()  # read after the ticks
    assert angle == finger.get_angle() < before - 0.1  # as the frames of the ticks say: closing
    assert len(torques) == 20
    scene.resume()
