"""Ownership: a controller changes only what it made, unless its owner shared the robot
(then others may steer it and attach their own parts to it). Two sessions, one scene."""

import json

import pytest

from server.core.protocol.session import Session


@pytest.fixture
def alice(scene):
    return Session(scene, "c1")


@pytest.fixture
def bob(scene):
    return Session(scene, "c2")


def ask(session, *ops):
    """Send ops as one batch; its answer."""
    [answer] = session.receive(json.dumps({"op": "batch", "id": 9, "ops": list(ops)}))
    return answer


def call(target, method, *args):
    return {"op": "call", "object": target, "method": method, "args": list(args)}


def ref(node_id):
    return {"ref": node_id}


@pytest.fixture
def hand(alice):
    assert ask(alice, {"op": "create", "object": "c1.h", "type": "EdgedHand"},
               {"op": "create", "object": "c1.f", "type": "EdgedFinger"})["op"] == "ok"
    return "c1.h"


@pytest.mark.parametrize("op", [
    call("c1.h", "setPosition", [1, 2, 3]),
    call("c1.h", "setAngles", 0.1, 0.2),
    call("c1.h/1", "setAngle", 0.3),
    call("c1.h/1", "setName", "mine now"),
    call("c1.h", "flexFingers", 0.5),
    call("c1.h", "addGUI", "taken"),
    call("c1.h", "share"),
    call("c1.f", "attachToSlot", ref("c1.h")),
    {"op": "delete", "object": "c1.h"},
    call("scene", "setTransforms", {"c1.f": [1, 0, 0, 0, 0, 0, 1]}),
])
def test_nobody_changes_what_is_not_theirs(scene, bob, hand, op):
    before = scene.snapshot()["nodes"]
    answer = ask(bob, op)
    assert answer["op"] == "error" and answer["code"] == "forbidden"
    assert answer["details"]["owner"] == "c1" and "belongs to c1" in answer["message"]
    assert scene.snapshot()["nodes"] == before


def test_own_parts_do_not_go_onto_an_unshared_robot_nor_others_into_mine(scene, bob, hand):
    assert ask(bob, {"op": "create", "object": "c2.f", "type": "EdgedFinger"})["op"] == "ok"
    answer = ask(bob, call("c2.f", "attachToSlot", ref("c1.h")))
    assert answer["code"] == "forbidden" and "share" in answer["message"]
    assert ask(bob, {"op": "create", "object": "c2.r", "type": "Robot"},
               call("c2.r", "attachChain", ref("c1.f")))["code"] == "forbidden"
    assert "c2.r" not in scene.nodes  # the failed batch applied nothing
    assert scene.nodes["c1.f"].parent is None


def test_a_shared_robot_is_steered_by_anyone_and_moved_only_by_its_owner(scene, alice, bob, hand):
    assert ask(alice, call(hand, "share"))["op"] == "ok"
    assert ask(bob, call(hand, "setAngles", -0.1, -0.2), call("c1.h/2", "setAngle", -0.5),
               call(hand, "flexFingers", 0.4))["op"] == "ok"
    assert scene.nodes["c1.h/2"].angle == -0.4  # flexed last
    for op in (call(hand, "setPosition", [5, 0, 0]), call(hand, "setName", "x"),
               {"op": "delete", "object": "c1.h/2"}, call("c1.f", "attachToSlot", ref(hand))):
        answer = ask(bob, op)
        assert answer["code"] in ("forbidden", "unknown_method") and answer["op"] == "error"
    answer = ask(bob, call(hand, "setPosition", [5, 0, 0]))
    assert "shared" in answer["message"] and answer["details"]["owner"] == "c1"


def test_others_attach_their_own_parts_to_a_shared_robot(scene, alice, bob, hand):
    ask(alice, call(hand, "share"))
    assert ask(bob, {"op": "create", "object": "c2.m", "type": "MotorZ"},
               {"op": "create", "object": "c2.f", "type": "EdgedFinger"},
               call(hand, "attachChain", ref("c2.m"), ref("c2.f")))["op"] == "ok"
    assert scene.nodes["c2.m"].root() is scene.nodes[hand]
    assert ask(bob, call("c2.f", "setPosition", [0, 1, 0]))["op"] == "ok"  # still bob's
    assert ask(alice, call("c2.f", "setPosition", [0, 2, 0]))["code"] == "forbidden"
    assert ask(alice, call(hand, "share", False))["op"] == "ok"
    assert ask(bob, call(hand, "setAngles", 0.1))["code"] == "forbidden"


def test_reading_sensing_and_watching_stay_open(scene, bob, hand):
    assert ask(bob, call(hand, "getAngles"), call(hand, "getParts"))["op"] == "ok"


def test_every_kind_that_names_objects_is_checked(scene):
    """Ownership looks only at parameters of NODE_KINDS: any kind whose binding resolves
    an object must be one of them."""
    from server.core.protocol.arguments import _KINDS, NODE_KINDS
    from server.core.model.parts import Box
    box = Box(scene, "c1.b")
    for kind, bind in _KINDS.items():
        named = []
        def resolve(node_id):
            named.append(node_id)
            return box
        for value in ({"ref": "c1.b"}, {"c1.b": [0, 0, 0, 0, 0, 0, 1]}, "c1.b"):
            try:
                bind(value, resolve, "test")
            except Exception:
                pass
        assert not named or kind in NODE_KINDS, kind


def test_only_the_scenes_keeper_or_a_controller_with_the_token_changes_its_physics(scene, alice, bob):
    # a stranger on the demo set it dynamic and made 100 balls: its viewers got 5 frames
    # in 80 s
    scene.keeper = "c1"
    refused = ask(bob, call("scene", "setPhysics", "dynamic"))
    assert refused["op"] == "error" and refused["code"] == "forbidden"
    assert "c1's" in refused["message"] and "--token" in refused["message"]
    assert scene.get_physics()["mode"] == "kinematic"
    assert ask(Session(scene, "c3", trusted=True), call("scene", "setPhysics", "dynamic"))["op"] == "ok"
    assert ask(alice, call("scene", "setPhysics", "kinematic"))["op"] == "ok"
    assert ask(bob, call("scene", "setCameraPosition", 1, 2, 3))["op"] == "ok"  # not the scene's kind
    scene.keeper = "the server"
    assert "the server's" in ask(alice, call("scene", "setPhysics", "dynamic"))["message"]
