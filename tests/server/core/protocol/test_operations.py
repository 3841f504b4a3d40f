"""Operations: checked messages become calls on a scene, and results their wire values."""

import dataclasses

import pytest

from server.core.kit.limits import DEFAULT
from server.core.protocol import api
from server.core.protocol.operations import RESULTS, Operations
from server.core.scene.scene import Scene
from server.core.kit.errors import LimitExceeded, OutOfRange, UnknownMethod, UnknownType


@pytest.fixture
def ops(scene):
    return Operations(scene, "c1")


def test_results_travel_as_refs_numbers_and_points(ops):
    assert ops.create("c1.1", "Robot", []) == {"ref": "c1.1"}
    ops.create("c1.2", "MotorZ", [-1, 1, 0.5])
    assert ops.call("c1.1", "attachChain", [{"ref": "c1.2"}]) == {"ref": "c1.2"}  # the last
    assert ops.call("c1.1", "setPosition", [1, 2, 3]) == {"ref": "c1.1"}  # itself
    assert ops.call("c1.1", "getMotors", []) == [{"ref": "c1.2"}]
    assert ops.call("c1.2", "getAngle", []) == 0.5
    assert ops.call("c1.1", "getPosition", []) == [1, 2, 3]
    ops.create("c1.3", "Sensor", [])
    ops.call("c1.3", "setPosition", [0, 1, 0])  # looking up, at nothing
    assert ops.call("c1.3", "senseDistance", []) == "Infinity"


def test_every_kind_of_result_the_table_names_travels(ops):
    kinds = {method.returns for spec in api.TYPES.values() for method in spec.methods}
    assert kinds <= set(RESULTS), kinds - set(RESULTS)  # getPhysics was an internal error
    ops.call("scene", "setPhysics", ["dynamic", {"gravity": 5}])
    physics = ops.call("scene", "getPhysics", [])
    assert physics["mode"] == "dynamic" and physics["gravity"] == 5


def test_an_unknown_type_or_method_is_refused_with_what_there_is(ops):
    with pytest.raises(UnknownType, match="'Wheel'; the types are .*Robot"):
        ops.create("c1.1", "Wheel", [])
    ops.create("c1.1", "Ball", [])
    with pytest.raises(UnknownMethod, match="Ball has no method 'fly'"):
        ops.call("c1.1", "fly", [])


def test_a_failing_op_of_a_batch_is_named_by_its_index(ops, scene):
    batch = {"op": "batch", "ops": [{"op": "create", "object": "c1.1", "type": "Ball"},
                                     {"op": "call", "object": "c1.1", "method": "setPosition",
                                      "args": [0, "up", 0]}]}
    with pytest.raises(Exception) as caught, scene.journal.transaction():
        ops.apply(batch)
    assert caught.value.message.startswith("batch op 1 (call): ")
    assert caught.value.details["index"] == 1
    assert "c1.1" not in scene.nodes  # the caller's transaction undid op 0 too


def test_a_batch_longer_than_its_limit_is_refused_whole():
    scene = Scene("small", dataclasses.replace(DEFAULT, batch_ops=2))
    try:
        ops = Operations(scene, "c1")
        three = [{"op": "create", "object": f"c1.{k}", "type": "Box"} for k in (1, 2, 3)]
        with pytest.raises(LimitExceeded) as caught:
            ops.apply({"op": "batch", "ops": three})
        assert caught.value.details == {"limit": "batchOps", "value": 2, "flag": "--limit batchOps=N"}
        assert not scene.nodes
    finally:
        scene.close()


def test_viewers_may_ping_and_read_but_nothing_that_changes_the_scene(ops):
    ops.create("c1.1", "MotorZ", [])
    assert not ops.mutates({"op": "ping"})
    assert not ops.mutates({"op": "call", "object": "c1.1", "method": "getAngle"})
    assert ops.mutates({"op": "call", "object": "c1.1", "method": "setAngle"})
    assert ops.mutates({"op": "delete", "object": "c1.1"})
    assert ops.apply({"op": "ping"}) == {"time": 0.0, "seq": 0}


def test_a_keeping_client_makes_kept_objects(ops, scene):
    ops.keep = True
    ops.create("c1.1", "Box", [])
    assert scene.nodes["c1.1"].kept
    with pytest.raises(OutOfRange):
        ops.create("c1.2", "MotorZ", [0, 1, 0, -1])  # a negative width
