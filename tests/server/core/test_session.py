"""Sessions: answers, permissions, id prefixes, ownership."""

import json


from server.core.session import Session


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
    monkeypatch.setattr("server.core.motor.Motor.set_name", broken)
    [error] = send(session, {"op": "batch", "id": 4, "ops": [
        {"op": "call", "object": "c1.1", "method": "setAngle", "args": [1]},
        {"op": "call", "object": "c1.1", "method": "setName", "args": ["x"]}]})
    assert error["code"] == "internal" and scene.nodes["c1.1"].angle == 0
