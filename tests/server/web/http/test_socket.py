"""The /ws endpoint with real connections: many clients, roles, frames, bad input."""

import json
import os
import signal
import threading
import time

import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

import virtual_prosthetics as vp
from server.core.protocol.messages import check_server_message
from tests.conftest import WAIT_SECONDS, eventually, start_server, stop_server

from ..ws_requests import next_message, request_all, wait_ticks

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first


def open_client(server, scene, role="controller"):
    # (an unbounded queue: a client that stops reading a while must not spend its close
    # handshake's 10 s waiting behind the frames it left unread)
    ws = connect(f"{server.ws}/ws?scene={scene}&role={role}", max_size=None,
                 max_queue=None).__enter__()
    hello = json.loads(ws.recv(timeout=WAIT_SECONDS))
    snapshot = json.loads(ws.recv(timeout=WAIT_SECONDS))
    check_server_message(hello)
    check_server_message(snapshot)
    return ws, hello, snapshot


def test_second_client_sees_the_first_ones_robot_and_its_motion(server, scene_name):
    first, hello, _ = open_client(server, scene_name)
    me = hello["client"]
    with first:
        request_all(first, [
            {"op": "create", "object": f"{me}.1", "type": "Robot"},
            {"op": "create", "object": f"{me}.2", "type": "MotorZ", "args": [-1, 1]},
            {"op": "call", "object": f"{me}.1", "method": "attachChain",
             "args": [{"ref": f"{me}.2"}]},
        ])
        wait_ticks(first)  # later changes come in frames, not as part of "added"
        second, hello2, snapshot = open_client(server, scene_name, "viewer")
        with second:
            assert hello2["client"] != me and hello2["role"] == "viewer"
            assert [n["id"] for n in snapshot["nodes"]] == [f"{me}.1", f"{me}.2", f"{me}.2/s0"]
            request_all(first, [{"op": "call", "object": f"{me}.2", "method": "setAngle",
                                 "args": [0.75]}])
            for _ in range(600):
                frame = next_message(second, "frame")
                check_server_message(frame)
                if f"{me}.1" in frame.get("angles", {}):
                    break
            assert frame["angles"] == {f"{me}.1": [0.75]}  # the robot's angles, in motor order


def test_viewer_cannot_change_anything(server, scene_name):
    owner, hello, _ = open_client(server, scene_name)
    me = hello["client"]
    with owner:
        request_all(owner, [{"op": "create", "object": f"{me}.1", "type": "MotorZ"}])
        viewer, vhello, _ = open_client(server, scene_name, "viewer")
        with viewer:
            viewer.send(json.dumps({"op": "call", "id": 1, "object": f"{me}.1",
                                    "method": "setAngle", "args": [1]}))
            error = next_message(viewer, "error")
            assert error["code"] == "forbidden" and error["id"] == 1
            viewer.send(json.dumps({"op": "delete", "id": 2, "object": f"{me}.1"}))
            assert next_message(viewer, "error")["code"] == "forbidden"
        [answer] = request_all(owner, [{"op": "call", "object": f"{me}.1", "method": "getAngle"}])
        assert answer["result"] == 0


def test_idle_frames_keep_time_and_sequence(server, scene_name):
    ws, _, snapshot = open_client(server, scene_name)
    with ws:
        frames = [next_message(ws, "frame") for _ in range(5)]
    # one after another (a connection that falls behind gets two ticks folded into one)
    assert all(a["seq"] < b["seq"] and a["time"] < b["time"] for a, b in zip(frames, frames[1:]))
    assert all(set(f) == {"op", "seq", "time"} for f in frames)
    assert frames[-1]["time"] > frames[0]["time"] >= snapshot["time"]


def test_disconnecting_removes_what_the_client_made(server, scene_name):
    watcher, _, _ = open_client(server, scene_name, "viewer")
    with watcher:
        maker, hello, _ = open_client(server, scene_name)
        me = hello["client"]
        request_all(maker, [{"op": "create", "object": f"{me}.1", "type": "EdgedHand"}])
        added = next_message(watcher, "added")
        maker.close()
        removed = next_message(watcher, "removed")
        assert sorted(removed["ids"]) == sorted(n["id"] for n in added["nodes"])
        assert f"{me}.1" in removed["ids"] and len(removed["ids"]) == 77
    deadline = time.monotonic() + WAIT_SECONDS
    while server.get(f"/api/scenes/{scene_name}")["objects"] and time.monotonic() < deadline:
        time.sleep(0.05)
    assert server.get(f"/api/scenes/{scene_name}")["objects"] == 0


def test_oversize_and_garbage_get_errors_and_the_connection_lives_on(server, scene_name):
    ws, hello, _ = open_client(server, scene_name)
    with ws:
        ws.send("x" * (2 << 20))
        assert next_message(ws, "error")["code"] == "too_large"
        ws.send(b'{"op": "ping", "id": 1}')  # binary: not taken as text
        binary = next_message(ws, "error")
        assert binary["code"] == "bad_message" and "binary" in binary["message"]
        ws.send("{nope")
        assert next_message(ws, "error")["code"] == "bad_json"
        [answer] = request_all(ws, [{"op": "ping"}])
        assert answer["op"] == "ok"


def test_bad_role_scene_name_or_engine_is_refused_with_a_reason(server):
    for query, word in (("scene=ok&role=admin", "role"), ("scene=bad%20name", "scene"),
                        ("scene=ok&engine=cannon", "pybullet")):
        with connect(f"{server.ws}/ws?{query}") as ws:
            error = json.loads(ws.recv(timeout=WAIT_SECONDS))
            assert error["op"] == "error" and error["code"] == "out_of_range"
            assert word in error["message"]
    ws, hello, _ = open_client(server, "ok")
    with ws:
        assert hello["engine"] == "pybullet"


def test_a_hundred_watched_sensors_come_with_every_frame(server, scene_name):
    ws, hello, _ = open_client(server, scene_name)
    me = hello["client"]
    with ws:
        heights = {f"{me}.s{k}": 0.1 + 0.05 * k for k in range(100)}
        request_all(ws, [{"op": "batch", "ops": [op for k, (sensor, height) in
                                                 enumerate(heights.items()) for op in (
            {"op": "create", "object": sensor, "type": "Sensor"},
            {"op": "call", "object": sensor, "method": "setPosition", "args": [0.3 * k, height, 0]},
            {"op": "call", "object": sensor, "method": "setRotation",
             "args": [3.141592653589793, 0, 0]},
            {"op": "call", "object": sensor, "method": "watch"})]}])
        wait_ticks(ws, 1)
        for _ in range(10):
            frame = next_message(ws, "frame")
            check_server_message(frame)
            readings = frame["sensors"]
            assert set(readings) == set(heights)
            for sensor, height in heights.items():
                assert abs(readings[sensor]["distance"] - height) < 1e-4


def test_frames_carry_contact_changes_to_every_client(server, scene_name):
    ws, hello, _ = open_client(server, scene_name)
    viewer, _, _ = open_client(server, scene_name, "viewer")
    me = hello["client"]
    with ws, viewer:
        request_all(ws, [{"op": "create", "object": f"{me}.b", "type": "Box"},
                         {"op": "call", "object": f"{me}.b", "method": "setPosition",
                          "args": [0, 0.4, 0]}])
        began = next_message(viewer, "frame")
        while "contacts" not in began:
            began = next_message(viewer, "frame")
        assert began["contacts"] == {"begin": [[f"{me}.b", "ground"]], "end": []}
        request_all(ws, [{"op": "call", "object": f"{me}.b", "method": "setPosition",
                          "args": [0, 0.6, 0]}])
        ended = next_message(viewer, "frame")
        while "contacts" not in ended:
            ended = next_message(viewer, "frame")
        assert ended["contacts"] == {"begin": [], "end": [[f"{me}.b", "ground"]]}


def test_messages_are_sent_uncompressed_even_when_the_client_offers_deflate(server, scene_name):
    # compressing on the loop every scene shares would hold every other scene's frames
    with connect(f"{server.ws}/ws?scene={scene_name}", compression="deflate") as ws:
        assert "Sec-WebSocket-Extensions" not in ws.response.headers
        assert json.loads(ws.recv(timeout=WAIT_SECONDS))["op"] == "hello"


def test_clients_change_only_their_own_objects_unless_shared(server, scene_name):
    alice, hello, _ = open_client(server, scene_name)
    bob, bob_hello, _ = open_client(server, scene_name)
    a = hello["client"]
    with alice, bob:
        request_all(alice, [{"op": "create", "object": f"{a}.h", "type": "EdgedHand"}])
        bob.send(json.dumps({"op": "call", "id": 1, "object": f"{a}.h", "method": "setAngles",
                             "args": [0.3]}))
        error = next_message(bob, "error")
        assert error["code"] == "forbidden" and error["details"]["owner"] == a
        request_all(alice, [{"op": "call", "object": f"{a}.h", "method": "share"}])
        request_all(bob, [{"op": "call", "object": f"{a}.h", "method": "setAngles",
                           "args": [0.3]}])
        for _ in range(600):  # alice sees bob steer her shared hand (its first motor)
            if next_message(alice, "frame").get("angles", {}).get(f"{a}.h", [None])[0] == 0.3:
                break
        else:
            raise AssertionError("the angle never reached the owner")
        bob.send(json.dumps({"op": "delete", "id": 2, "object": f"{a}.h"}))
        assert next_message(bob, "error")["code"] == "forbidden"
        [robot] = [r for r in server.get(f"/api/scenes/{scene_name}/robots")]
        assert (robot["owner"], robot["shared"]) == (a, True)



def test_a_client_that_comes_back_in_time_is_itself_again(server, scene_name):
    """The shared server's grace period is 1 s: back within it, nothing was lost."""
    first, hello, _ = open_client(server, scene_name)
    me, resume = hello["client"], hello["resume"]
    with first:
        request_all(first, [{"op": "create", "object": f"{me}.1", "type": "Box"}])
    again, hello2, snapshot = open_client(server, scene_name + f"&resume={resume}")
    with again:
        assert hello2["client"] == me and f"{me}.1" in [n["id"] for n in snapshot["nodes"]]
        time.sleep(1.5)
        assert f"{me}.1" in [n["id"] for n in server.nodes(scene_name)]
        request_all(again, [{"op": "call", "object": f"{me}.1", "method": "setPosition",
                             "args": [[1, 2, 3]]}])  # still its owner
    forged, hello3, _ = open_client(server, scene_name + f"&resume={me}:{'0' * 32}")
    with forged:
        assert hello3["client"] != me
    deadline = time.monotonic() + WAIT_SECONDS
    while f"{me}.1" in [n["id"] for n in server.nodes(scene_name)]:
        assert time.monotonic() < deadline, "what a client made goes after the grace period"
        time.sleep(0.1)


def test_keep_leaves_what_a_client_made_in_the_scene(server, scene_name):
    maker, hello, _ = open_client(server, scene_name + "&keep=true")
    me = hello["client"]
    with maker:
        request_all(maker, [{"op": "create", "object": f"{me}.1", "type": "Box"}])
    time.sleep(1.5)
    assert f"{me}.1" in [n["id"] for n in server.nodes(scene_name)]


def test_with_the_default_grace_a_script_robots_go_ten_seconds_after_it_leaves():
    server = start_server("--no-demo")  # leaveGraceSeconds 10, as shipped
    try:
        with vp.connect(server.ws, scene="default") as script:
            hand = vp.EdgedHand()
            script.sync()
        left = time.monotonic()
        time.sleep(8)
        assert [r["id"] for r in server.robots("default")] == [hand.id]  # still in its grace
        while server.robots("default"):  # gone once the grace is over (a loaded machine
            assert time.monotonic() - left < 10 + WAIT_SECONDS, "the robot stayed"  # may lag)
            time.sleep(0.1)
        assert time.monotonic() - left >= 10
    finally:
        stop_server(server)


def test_a_connection_its_client_replaced_is_closed_with_a_reason_and_stays_closed(server, scene_name):
    first, hello, _ = open_client(server, scene_name)
    with first:
        again, hello2, _ = open_client(server, scene_name + f"&resume={hello['resume']}")
        with again:
            with pytest.raises(ConnectionClosed) as closed:
                while True:
                    first.recv(timeout=WAIT_SECONDS)
            assert closed.value.rcvd.code == 4001 and "replaced" in closed.value.rcvd.reason
            assert hello2["client"] == hello["client"]


def test_a_python_client_replaced_elsewhere_does_not_fight_back(server, scene_name):
    with vp.connect(server.ws, scene=scene_name) as client:
        resume = client.connection.core.resume
        with connect(f"{server.ws}/ws?scene={scene_name}&resume={resume}") as thief:
            json.loads(thief.recv(timeout=WAIT_SECONDS))
            eventually(lambda: client.connection.closed is not None)
            assert "replaced" in client.connection.closed
            thief.send(json.dumps({"op": "ping", "id": 1}))
            while json.loads(thief.recv(timeout=WAIT_SECONDS))["op"] != "ok":
                pass  # the newer connection is still the client's


def test_a_client_sending_faster_than_its_scene_applies_is_slowed_not_refused(server, scene_name):
    """The issue's probe: 100 setAngle calls a step, as fast as the socket takes them.
    Every one is applied (none refused), and another client's request does not wait
    behind the backlog: the server stops reading the flooder's socket instead."""
    flooder, hello, _ = open_client(server, scene_name)
    me, steps, per_step = hello["client"], 120, 100
    with flooder:
        request_all(flooder, [{"op": "create", "object": f"{me}.m", "type": "MotorZ",
                               "args": [-1, 1]}])
        answered: list[str] = []

        def read_answers() -> None:
            while len(answered) < steps * per_step:
                message = json.loads(flooder.recv(timeout=60))
                if message["op"] in ("ok", "error") and message.get("id", 0) < 10 ** 6:
                    answered.append(message["op"] if message["op"] == "ok" else message["code"])

        reader = threading.Thread(target=read_answers)
        reader.start()
        bystander, _, _ = open_client(server, scene_name, "viewer")
        with bystander:
            sender = threading.Thread(target=lambda: [flooder.send(json.dumps([
                {"op": "call", "id": step * per_step + k + 1, "object": f"{me}.m",
                 "method": "setAngle", "args": [k / per_step]} for k in range(per_step)]))
                for step in range(steps)])
            sender.start()
            eventually(lambda: answered)  # the flood is being applied
            request_all(bystander, [{"op": "ping"}])
            backlog_then = steps * per_step - len(answered)
            sender.join(60)
            reader.join(60)
    assert answered == ["ok"] * (steps * per_step)
    assert backlog_then > 0  # the bystander was answered before the flood was done


def test_a_client_held_back_while_its_scene_is_busy_is_not_closed_by_the_keepalive(scene_name):
    """What a driver met while a thousand viewers joined its scene: the scene (here stopped)
    applies nothing, so the server stops reading the client, whose pongs then wait unread;
    the keepalive closed it (1011) though it had answered every ping."""
    # pings every 2 s, each answer due within 2 s (the test process answers them, loaded)
    server = start_server("--no-demo", "--ping-seconds", "2")
    try:
        client, hello, _ = open_client(server, scene_name)
        with client:
            me = hello["client"]
            request_all(client, [{"op": "create", "object": f"{me}.m", "type": "MotorZ"}])
            pid = server.figures(scene_name)["pid"]
            os.kill(pid, signal.SIGSTOP)
            try:
                step = json.dumps([{"op": "call", "object": f"{me}.m", "method": "setAngle",
                                    "args": [k / 1000]} for k in range(200)])
                for _ in range(20):  # past what may wait unapplied: the server stops reading
                    client.send(step)
                time.sleep(5.0)  # past a ping's deadline (sent at 2 s, due at 4)
            finally:
                os.kill(pid, signal.SIGCONT)
            assert request_all(client, [{"op": "ping"}])[0]["op"] == "ok"  # not closed: 1011
    finally:
        stop_server(server)
