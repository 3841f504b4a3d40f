"""A scene's process loop, driven through a real pipe (the loop runs on a thread here)."""

import json
import multiprocessing
import os
import signal
import subprocess
import sys
import threading
import time

import pytest
from websockets.sync.client import connect

from server.core.kit.limits import DEFAULT
from server.core.scene.scene import Scene
from server.core.kit.errors import UnknownObject
from server.web.http.rest import _robot
from server.web.process.messages import (Admit, Answers, Ask, Frame, Idle, Join, Leave, Metrics, Read,
                                         Reply, Stop, Text)
from server.web.process.worker import SceneWorker
from tests.conftest import ROOT, WAIT_SECONDS, alive, descendants, eventually, start_server, stop_server

from ..ws_requests import request_all, wait_ticks


@pytest.fixture
def worker():
    server_end, scene_end = multiprocessing.Pipe()
    scene = Scene("w", DEFAULT.with_values(["leaveGraceSeconds=1"]))
    loop = SceneWorker(scene_end, scene, 60.0)
    thread = threading.Thread(target=loop.run)
    server_end.born = time.monotonic()  # the scene's clock starts after this
    thread.start()
    yield server_end
    server_end.send([Stop()])
    thread.join(timeout=WAIT_SECONDS)
    assert not thread.is_alive()
    scene.close()


def events_until(pipe, kind, count=1):
    """Events received until ``count`` of ``kind`` came; those of that kind."""
    found = []
    while len(found) < count:
        assert pipe.poll(WAIT_SECONDS), f"no {kind.__name__} event"
        found += [event for event in pipe.recv() if isinstance(event, kind)]
    return found


def test_a_client_joins_sends_and_gets_its_answers_in_order(worker):
    worker.send([Join(7, "c7", "controller")])
    (number, (hello, snapshot)), = [(a.cid, a.items) for a in events_until(worker, Admit)]
    assert number == 7 and hello.message["client"] == "c7" and snapshot.op == "snapshot"
    texts = [json.dumps({"op": "create", "object": f"c7.{k}", "type": "Box", "id": k})
             for k in range(1, 4)]
    worker.send([Text(7, text) for text in texts])
    answers = events_until(worker, Answers, 3)
    assert [(a.cid, a.items[0].message["id"], a.applied) for a in answers] == [
        (7, k, len(texts[k - 1])) for k in range(1, 4)]
    frame, = events_until(worker, Frame)
    assert frame.items[0].op in ("added", "frame")


def test_reads_reply_with_json_or_the_error_with_its_details(worker):
    worker.send([Join(1, "c1", "controller"),
                 Text(1, json.dumps({"op": "create", "object": "c1.r", "type": "Robot"})),
                 Ask(5, Read(_robot, ("c1.r",))), Ask(6, Read(_robot, ("c1.nope",)))])
    ok, refused = events_until(worker, Reply, 2)
    assert (ok.number, ok.ok) == (5, True) and json.loads(ok.value)["id"] == "c1.r"
    assert (refused.number, refused.ok) == (6, False) and isinstance(refused.value, UnknownObject)
    assert refused.value.details == {"object": "c1.nope"}


def nodes_of(worker, number):
    worker.send([Ask(number, Read(Scene.snapshot))])
    reply, = events_until(worker, Reply)
    assert reply.ok
    return [node["id"] for node in json.loads(reply.value)["nodes"]]


def test_a_leaving_client_takes_its_objects_along_after_the_grace_period(worker):
    worker.send([Join(1, "c1", "controller"),
                 Text(1, json.dumps({"op": "create", "object": "c1.b", "type": "Box"})),
                 Leave(1)])
    left = time.monotonic()
    assert nodes_of(worker, 2) == ["c1.b"]  # still there: it may come back
    while nodes_of(worker, 3) and time.monotonic() < left + 5:
        time.sleep(0.05)
    assert nodes_of(worker, 4) == [] and time.monotonic() - left >= 1


def test_a_client_back_within_the_grace_period_keeps_everything(worker):
    worker.send([Join(1, "c1", "controller"),
                 Text(1, json.dumps({"op": "create", "object": "c1.b", "type": "Box"})),
                 Leave(1), Join(2, "c1", "controller", "c1:key", False)])
    admitted, = events_until(worker, Admit, 2)[1:]
    hello = admitted.items[0]
    assert hello.message["client"] == "c1" and hello.message["resume"] == "c1:key"
    time.sleep(1.5)
    assert nodes_of(worker, 3) == ["c1.b"]


def test_a_client_that_keeps_leaves_its_objects_for_good(worker):
    worker.send([Join(1, "c1", "controller", None, True),
                 Text(1, json.dumps({"op": "create", "object": "c1.b", "type": "Box"})),
                 Leave(1)])
    time.sleep(1.5)
    assert nodes_of(worker, 2) == ["c1.b"]


def scene_clock(scene):
    return {"time": scene.time, "seq": scene.seq}


def test_a_scene_nobody_is_in_stops_ticking_and_its_clock_catches_up_when_asked(worker):
    events_until(worker, Idle)  # says so, then sends nothing: no frames for nobody
    idle = time.monotonic()  # the scene's clock started before this
    assert not worker.poll(0.3)
    asked = time.monotonic()
    worker.send([Ask(1, Read(scene_clock))])
    reply = events_until(worker, Reply)[0]
    ok, clock, answered = reply.ok, json.loads(reply.value), time.monotonic()
    tick = 1 / 60
    assert ok and asked - idle - tick <= clock["time"] <= answered - worker.born + tick
    assert clock["seq"] <= 5  # a tick or two, not 20 a third of a second
    worker.send([Join(2, "c2", "viewer")])
    events_until(worker, Admit)
    frames = events_until(worker, Frame, 5)  # someone is in: 60 ticks a second again
    assert len(frames) == 5


def test_asking_a_sleeping_scene_for_its_figures_does_not_wake_it(worker):
    events_until(worker, Idle)
    for number in range(3):
        worker.send([Ask(number, Metrics())])
        reply, = events_until(worker, Reply)
        assert reply.ok and reply.value["ticks"] <= 2
        assert worker.poll(WAIT_SECONDS) and worker.recv() == [Idle()]  # asleep again at once
    assert not worker.poll(0.3)  # and nothing more: it did not tick for the questions
    worker.send([Ask(9, Read(scene_clock))])
    assert json.loads(events_until(worker, Reply)[0].value)["seq"] <= 3


def test_a_dynamic_scene_nobody_watches_ticks_until_everything_rests(worker):
    worker.send([Join(1, "c1", "controller"),
                 Text(1, json.dumps({"op": "batch", "ops": [
                     {"op": "create", "object": "c1.b", "type": "Ball", "args": [0.2]},
                     {"op": "call", "object": "c1.b", "method": "keep", "args": []},
                     {"op": "call", "object": "c1.b", "method": "setPosition", "args": [0, 3, 0]},
                     {"op": "call", "object": "scene", "method": "setPhysics", "args": ["dynamic"]}]})),
                 Leave(1)])
    events_until(worker, Answers)
    started = time.monotonic()
    events_until(worker, Idle)  # once the ball lies still (the grace period is over before)
    assert time.monotonic() - started > 0.7  # three metres take 0.78 s to fall
    worker.send([Ask(2, Read(_height))])
    reply, = events_until(worker, Reply)
    assert reply.ok and json.loads(reply.value) == pytest.approx(0.2, abs=0.01)  # it fell while nobody watched


def _height(scene):
    return scene.get("c1.b").position[1]


def test_a_paused_scene_ticks_only_when_stepped_and_the_steps_frames_come_before_the_answer(worker):
    worker.send([Join(1, "c1", "controller"),
                 Text(1, json.dumps({"op": "call", "object": "scene", "method": "pause",
                                         "id": 1}))])
    events_until(worker, Answers)
    time.sleep(0.3)  # 18 ticks' time: a running scene would have sent frames of it
    worker.send([Text(1, json.dumps({"op": "call", "object": "scene", "method": "getTime",
                                         "id": 2}))])
    answers, = events_until(worker, Answers)
    paused_at = answers.items[0].message["result"]
    worker.send([Text(1, json.dumps({"op": "call", "object": "scene", "method": "step",
                                         "args": [3], "id": 3}))])
    events = []
    while not any(isinstance(event, Answers) for event in events):
        assert worker.poll(WAIT_SECONDS), "no answer to step"
        events += worker.recv()
    frames = [m.message for event in events if isinstance(event, Frame) for m in event.items
              if m.op == "frame"]
    assert [f["time"] - paused_at for f in frames] == pytest.approx([1 / 60, 2 / 60, 3 / 60])
    assert isinstance(events[-1], Answers) and events[-1].items[0].message["id"] == 3


def physics_answer(worker, cid, number):
    worker.send([Text(cid, json.dumps({"op": "call", "object": "scene", "method": "setPhysics",
                                          "args": ["dynamic"], "id": number}))])
    while True:
        answers, = events_until(worker, Answers)
        answer, = answers.items
        if answer.message["id"] == number:
            return answer.message


def test_the_first_controller_keeps_the_scene_until_it_has_gone_for_good(worker):
    worker.send([Join(1, "v1", "viewer"), Join(2, "c2", "controller"),
                 Join(3, "c3", "controller"), Join(4, "c4", "controller", None, False, True)])
    events_until(worker, Admit, 4)
    refused = physics_answer(worker, 3, 10)
    assert refused["code"] == "forbidden" and "c2's" in refused["message"]
    assert physics_answer(worker, 4, 11)["op"] == "ok"  # it presented the control token
    assert physics_answer(worker, 2, 12)["op"] == "ok"
    worker.send([Leave(2)])
    time.sleep(0.2)
    assert physics_answer(worker, 3, 13)["code"] == "forbidden"  # c2 may still come back
    deadline = time.monotonic() + WAIT_SECONDS
    while physics_answer(worker, 3, 14)["op"] != "ok":  # gone after its grace: c3 keeps it
        assert time.monotonic() < deadline
        time.sleep(0.1)


def test_a_busy_recording_scene_ends_with_the_server_and_its_recording_stays_readable(tmp_path):
    # kill -9 of the server left a busy scene (3.27 GB, 31 % CPU) running 186 s later and
    # a recording one alive 32 min later
    server = start_server("--no-demo", "--state-dir", str(tmp_path))
    try:
        with connect(f"{server.ws}/ws?scene=busy", max_size=None, max_queue=None) as ws:
            me = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
            request_all(ws, [{"op": "call", "object": "scene", "method": "setPhysics",
                              "args": ["dynamic"]}])
            request_all(ws, [{"op": "batch", "ops": [
                {"op": "create", "object": f"{me}.{i}", "type": "Ball", "args": [0.2]}
                for i in range(300)]}])
            _, started = server.post("/api/scenes/busy/recordings")
            wait_ticks(ws, 10)
            processes = descendants(server.process.pid)
            assert len(processes) >= 2  # the fork server and the scene's process at least
            os.kill(server.process.pid, signal.SIGKILL)
            server.process.wait(timeout=WAIT_SECONDS)
        eventually(lambda: not any(alive(pid) for pid in processes))
    finally:
        for pid in descendants(server.process.pid):
            os.kill(pid, signal.SIGKILL)
    again = start_server("--no-demo", "--state-dir", str(tmp_path))
    try:
        listed = {r["id"]: r for r in again.get("/api/recordings")}
        assert listed[started["id"]]["state"] == "stopped", listed[started["id"]]
        assert listed[started["id"]]["stopped"] == "the scene stopped"
        assert again.get(f"/api/recordings/{started['id']}/at?time=0")["messages"]
    finally:
        stop_server(again)


def test_a_scene_process_loads_no_asyncio():
    """Its loop is plain: commands from a pipe, ticks on a clock (an event loop's machinery
    in every scene's process would be memory and start-up time for nothing)."""
    loaded = subprocess.run(
        [sys.executable, "-c", "import sys, server.web.process.worker; "
                               "print(sorted(m for m in sys.modules if m.startswith('asyncio')))"],
        cwd=ROOT, capture_output=True, text=True, check=True).stdout
    assert loaded.strip() == "[]"


def pipe_messages_until_answer(pipe, number):
    """The events of every pipe message until the one that answers request ``number``,
    message by message."""
    messages = []
    while not any(isinstance(e, Answers) and e.items and e.items[0].message.get("id") == number
                  for e in (messages[-1] if messages else [])):
        assert pipe.poll(WAIT_SECONDS), f"no answer to {number}"
        messages.append(pipe.recv())
    return messages


def test_a_batch_of_setters_is_answered_with_the_next_frame_and_a_read_at_once(worker):
    worker.send([Join(1, "c1", "controller"),
                 Text(1, json.dumps({"op": "create", "object": "c1.b", "type": "Box", "id": 1}))])
    pipe_messages_until_answer(worker, 1)
    while not any(m.op == "added" for frame in events_until(worker, Frame) for m in frame.items):
        pass  # until the box is in a frame: the next ones carry only what changes
    worker.send([Text(1, json.dumps({"op": "batch", "id": 2, "ops": [
        {"op": "call", "object": "c1.b", "method": "setPosition", "args": [1, 2, 3]},
        {"op": "call", "object": "c1.b", "method": "setRotation", "args": [0, 0.5, 0]}]}))])
    *_, last = pipe_messages_until_answer(worker, 2)
    at = next(k for k, e in enumerate(last) if isinstance(e, Answers) and e.items)
    answer = last[at].items[0].message
    assert (answer["op"], answer["result"]) == ("ok", [None, None])
    moved = [m.message for e in last[at + 1:] if isinstance(e, Frame) for m in e.items
             if m.op == "frame"]  # the answer leaves with the frame that shows its change
    assert moved and moved[0]["poses"]["c1.b"][:3] == pytest.approx([1, 2, 3])
    worker.send([Text(1, json.dumps({"op": "call", "object": "scene", "method": "getTime",
                                     "id": 3}))])
    *_, last = pipe_messages_until_answer(worker, 3)
    assert isinstance(last[-1], Answers) and not any(isinstance(e, Frame) for e in last)
    assert last[-1].items[0].message["result"] > 0


def test_a_batch_of_setters_in_a_paused_scene_is_answered_at_once(worker):
    """A paused scene's next frame waits for a step, which its script may send only once
    this answer came: nothing is held for it."""
    worker.send([Join(1, "c1", "controller"),
                 Text(1, json.dumps({"op": "batch", "id": 1, "ops": [
                     {"op": "create", "object": "c1.b", "type": "Box"},
                     {"op": "call", "object": "scene", "method": "pause"}]}))])
    pipe_messages_until_answer(worker, 1)
    worker.send([Text(1, json.dumps({"op": "batch", "id": 2, "ops": [
        {"op": "call", "object": "c1.b", "method": "setPosition", "args": [1, 2, 3]}]}))])
    *_, last = pipe_messages_until_answer(worker, 2)
    assert isinstance(last[-1], Answers) and not any(isinstance(e, Frame) for e in last)
    assert last[-1].items[0].message["result"] == [None]
