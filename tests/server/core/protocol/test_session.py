"""Sessions: answers, permissions, id prefixes, ownership."""

import json

from server.core.kit.limits import DEFAULT as LIMITS
from server.core.protocol.session import Session


def send(session, *messages):
    return session.receive(json.dumps(list(messages)))


def test_answers_carry_results_and_changes(scene):
    session = Session(scene, "c1")
    create, call = send(session, {"op": "create", "id": 1, "object": "c1.1", "type": "MotorZ",
                                  "args": [-1, 1]},
                        {"op": "call", "id": 2, "object": "c1.1", "method": "setAngle",
                         "args": [3]})
    assert create["result"] == {"ref": "c1.1"}
    assert [n["id"] for n in create["changes"]["added"]] == ["c1.1", "c1.1/s0"]
    assert call == {"op": "ok", "id": 2, "changes": {"angles": {"c1.1": 1.0}}}


def test_fire_and_forget_is_silent_unless_it_fails(scene):
    session = Session(scene, "c1")
    assert send(session, {"op": "create", "object": "c1.1", "type": "Box"}) == []
    [error] = send(session, {"op": "call", "object": "c1.1", "method": "fly"})
    assert error["id"] is None and error["request"] == "call"
    assert error["code"] == "unknown_method"


def test_viewer_may_read_but_not_change(scene):
    Session(scene, "c1").receive(json.dumps(
        {"op": "create", "object": "c1.1", "type": "MotorZ"}))
    viewer = Session(scene, "c2", "viewer")
    denied, read = send(viewer,
                        {"op": "call", "id": 1, "object": "c1.1", "method": "setAngle",
                         "args": [1]},
                        {"op": "call", "id": 2, "object": "c1.1", "method": "getAngle"})
    assert denied["code"] == "forbidden" and read["result"] == 0
    [denied] = send(viewer, {"op": "create", "id": 3, "object": "c2.1", "type": "Box"})
    assert denied["code"] == "forbidden" and "c2.1" not in scene.nodes


def test_new_ids_must_carry_the_client_prefix(scene):
    session = Session(scene, "c1")
    for bad in ("c2.1", "c1", "c1./x", "c10.1"):
        [error] = send(session, {"op": "create", "id": 1, "object": bad, "type": "Box"})
        assert error["code"] == "foreign_id", bad
    assert scene.nodes == {}


def test_closing_deletes_what_the_client_made(scene):
    mine, theirs = Session(scene, "c1"), Session(scene, "c2")
    send(mine, {"op": "create", "object": "c1.1", "type": "EdgedHand"})
    send(theirs, {"op": "create", "object": "c2.1", "type": "Box"})
    assert mine.close() == ["c1.1"]
    assert list(scene.nodes) == ["c2.1"]


def test_internal_errors_are_reported_and_undone(scene, monkeypatch):
    session = Session(scene, "c1")
    send(session, {"op": "create", "object": "c1.1", "type": "MotorZ"})

    def broken(self, name):
        raise ZeroDivisionError("bug")
    monkeypatch.setattr("server.core.model.motor.Motor.set_name", broken)
    [error] = send(session, {"op": "batch", "id": 4, "ops": [
        {"op": "call", "object": "c1.1", "method": "setAngle", "args": [1]},
        {"op": "call", "object": "c1.1", "method": "setName", "args": ["x"]}]})
    assert error["code"] == "internal" and scene.nodes["c1.1"].angle == 0


def test_sensing_errors_name_what_was_wrong(scene):
    session = Session(scene, "c1")
    send(session, {"op": "create", "object": "c1.s", "type": "Sensor"},
         {"op": "create", "object": "c1.u", "type": "Sensor"},
         {"op": "create", "object": "c1.r", "type": "Robot"},
         {"op": "delete", "object": "c1.s"})
    deleted, robot, part, word, ground, laser = send(
        session,
        {"op": "call", "id": 1, "object": "c1.s", "method": "senseDistance"},
        {"op": "call", "id": 2, "object": "c1.r", "method": "senseTouch"},
        {"op": "call", "id": 3, "object": "c1.u", "method": "senseObject",
         "args": [{"ref": "c1.r"}]},
        {"op": "call", "id": 4, "object": "c1.u", "method": "senseObject", "args": ["floor"]},
        {"op": "call", "id": 5, "object": "c1.u", "method": "senseObject", "args": ["ground"]},
        {"op": "create", "id": 6, "object": "c1.t", "type": "Sensor",
         "args": [True, "not a colour!"]})
    assert deleted["code"] == "unknown_object" and "was deleted" in deleted["message"]
    assert robot["code"] == "unknown_method" and "Robot has no method" in robot["message"]
    assert part["code"] == "wrong_type" and "c1.r is a Robot" in part["message"]
    assert word["code"] == "wrong_type" and "'floor'" in word["message"]
    assert ground == {"op": "ok", "id": 5, "result": False}
    assert laser["code"] == "wrong_type" and "c1.t" not in scene.nodes



def test_what_a_client_keeps_stays_with_what_hangs_below_it(scene):
    mine, theirs = Session(scene, "c1"), Session(scene, "c2")
    for op in ({"op": "create", "object": "c1.arm", "type": "Robot"},
               {"op": "create", "object": "c1.m", "type": "MotorZ"},
               {"op": "call", "object": "c1.arm", "method": "attachChain", "args": [{"ref": "c1.m"}]},
               {"op": "call", "object": "c1.arm", "method": "keep"},
               {"op": "call", "object": "c1.arm", "method": "share"},
               {"op": "create", "object": "c1.loose", "type": "Box"}):
        send(mine, op)
    send(theirs, {"op": "create", "object": "c2.b", "type": "Ball"})
    send(theirs, {"op": "call", "object": "c2.b", "method": "attachToSlot", "args": [{"ref": "c1.m"}]})
    [refused] = send(theirs, {"op": "call", "id": 3, "object": "c1.arm", "method": "keep", "args": [False]})
    assert refused["code"] == "forbidden"  # keeping is the owner's call
    assert sorted(mine.close()) == ["c1.loose"]
    assert sorted(theirs.close()) == ["c2.b"]  # not kept by being on a kept robot
    assert sorted(scene.nodes) == ["c1.arm", "c1.m", "c1.m/s0"]
    assert scene.get("c1.arm").describe()["kept"] is True and not scene.get("c1.m").describe()["kept"]


def test_a_connection_that_keeps_keeps_everything_it_makes(scene):
    keeper = Session(scene, "c1")
    keeper.operations.keep = True
    send(keeper, {"op": "create", "object": "c1.1", "type": "EdgedHand"})
    assert keeper.close() == [] and len(scene.nodes) == 77  # the hand and all inside it

def test_viewers_may_watch_and_a_closed_client_stops_watching(scene):
    Session(scene, "c1").receive(json.dumps({"op": "create", "object": "c1.s",
                                             "type": "Sensor"}))
    viewer = Session(scene, "c2", "viewer")
    [answer] = send(viewer, {"op": "call", "id": 1, "object": "c1.s", "method": "watch"})
    assert answer == {"op": "ok", "id": 1} and scene.watches.ids() == ["c1.s"]
    viewer.close()
    assert scene.watches.ids() == []


def test_watching_past_the_limit_fails_and_watches_nothing(scene):
    session = Session(scene, "c1")
    count = LIMITS.watched_sensors + 1
    send(session, {"op": "batch", "ops": [{"op": "create", "object": f"c1.{k}",
                                           "type": "Sensor"} for k in range(count)]})
    [error] = send(session, {"op": "batch", "id": 1, "ops": [
        {"op": "call", "object": f"c1.{k}", "method": "watch"} for k in range(count)]})
    assert error["code"] == "limit_exceeded" and error["details"]["index"] == count - 1
    assert f"at most {count - 1} sensors" in error["message"]
    assert len(scene.watches) == 0


def test_what_follows_a_step_in_one_text_sees_the_world_it_stepped_to(scene):
    session = Session(scene, "c1")
    taken = []

    def take() -> None:  # as the process serving the scene takes a step's ticks
        for _ in range(scene.clock.take()):
            taken.append(scene.tick(1 / 60))
    session.on_step = take
    before = scene.time
    pause, step, time = send(session, {"op": "call", "id": 1, "object": "scene", "method": "pause"},
                             {"op": "call", "id": 2, "object": "scene", "method": "step", "args": [3]},
                             {"op": "call", "id": 3, "object": "scene", "method": "getTime"})
    assert len(taken) == 3 and time["result"] == before + 3 / 60
    session.on_step = None  # without a process to take them, the ticks wait for the text's end
    [time] = send(session, {"op": "call", "object": "scene", "method": "step", "args": [2]},
                  {"op": "call", "id": 4, "object": "scene", "method": "getTime"})
    assert time["result"] == before + 3 / 60 and scene.clock.owed == 2
