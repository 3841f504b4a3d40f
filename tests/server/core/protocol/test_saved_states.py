"""Saved states: a scene put back as it was, in a fresh world, gives the same steps bit for
bit every time; what it cannot do is refused with nothing changed."""

from __future__ import annotations

import pytest

from server.core.kit.limits import Limits
from server.core.protocol.operations import Operations
from server.core.protocol.scene_document import export_scene
from server.core.scene.scene import Scene
from server.core.kit.errors import Forbidden, LimitExceeded, UnknownObject


def ref(node_id: str) -> dict[str, str]:
    return {"ref": node_id}


def hand_over_ball(limits: Limits = Limits()) -> tuple[Scene, Operations]:
    """A dynamic scene: an edged hand over a ball on a box, and a sensor on the ball."""
    scene = Scene("lab", limits=limits)
    ops = Operations(scene, "c1")
    scene.keeper = "c1"
    ops.call("scene", "setPhysics", ["dynamic"])
    for object_id, type_name, args in [("c1.1", "EdgedHand", [True]), ("c1.2", "Box", [3, 1, 3]),
                                       ("c1.3", "Ball", [0.6]), ("c1.4", "Sensor", [False])]:
        ops.create(object_id, type_name, args)
    ops.call("c1.1", "setPosition", [0, 2.6, 0])
    ops.call("c1.1", "setRotation", [3.14159, 0, 0])
    ops.call("c1.2", "setPosition", [0, 0.5, 0])
    ops.call("c1.2", "setStatic", [True])
    ops.call("c1.3", "setPosition", [0.1, 1.6, -1.2])
    ops.call("c1.4", "attachToSlot", [ref("c1.3"), 0])
    ops.call("c1.4", "watch", [])
    scene.tick(1 / 60)
    return scene, ops


def run(scene: Scene, ops: Operations, ticks: int = 40) -> list[tuple]:
    """Close the hand on the ball and step; every part's pose after every tick."""
    ops.call("c1.1", "flexFingers", [1.2])
    ops.call("c1.1", "setPosition", [0, 2.2, 0])
    poses = []
    for _ in range(ticks):
        scene.tick(1 / 60)
        poses.append(tuple((node.id, node.position, node.quaternion) for node in scene.in_order_made()))
    return poses


def test_steps_after_a_restore_are_the_same_every_time():
    scene, ops = hand_over_ball()
    state = ops.call("scene", "saveState", [])
    first = run(scene, ops)
    ops.call("scene", "restoreState", [state])
    again = run(scene, ops)
    ops.call("scene", "restoreState", [state])
    third = run(scene, ops)
    assert again == third
    assert again[-1] != again[0]  # things moved: the hand closed and went down
    ball = [p for p in again[-1] if p[0] == "c1.3"][0]
    assert ball[1][1] == pytest.approx([p for p in first[-1] if p[0] == "c1.3"][0][1][1], abs=0.05)


def test_a_restore_puts_back_what_changed_and_what_was_watched():
    scene, ops = hand_over_ball()
    before = export_scene(scene, embed_assets=False)
    state = ops.call("scene", "saveState", [])
    run(scene, ops, 10)
    ops.call("c1.3", "setMass", [2.5])
    ops.call("c1.4", "watch", [False])
    scene.delete(scene.get("c1.2"))
    ops.create("c1.9", "Box", [1, 1, 1])
    ops.call("scene", "restoreState", [state])
    assert export_scene(scene, embed_assets=False) == before
    assert "c1.9" not in scene.nodes and "c1.4" in scene.watches
    assert scene.restored  # the process sends everyone a snapshot


def test_unknown_states_and_other_clients_objects_are_refused_with_nothing_changed():
    scene, ops = hand_over_ball()
    state = ops.call("scene", "saveState", [])
    with pytest.raises(UnknownObject, match="no saved state 'state-9' in scene lab \\(kept: state-1\\)"):
        ops.call("scene", "restoreState", ["state-9"])
    Operations(scene, "c2").create("c2.1", "Ball", [0.2])
    before = export_scene(scene, embed_assets=False)
    with pytest.raises(Forbidden, match="would replace objects of c2"):
        ops.call("scene", "restoreState", [state])
    assert export_scene(scene, embed_assets=False) == before and not scene.restored


def test_only_the_keeper_restores():
    scene, ops = hand_over_ball()
    state = ops.call("scene", "saveState", [])
    with pytest.raises(Forbidden, match="c1's"):
        Operations(scene, "c2").call("scene", "restoreState", [state])


def test_a_scene_keeps_its_limit_of_states_and_forgetting_frees_one():
    scene, ops = hand_over_ball(Limits(saved_states=2))
    first = ops.call("scene", "saveState", [])
    ops.call("scene", "saveState", [])
    with pytest.raises(LimitExceeded) as refused:
        ops.call("scene", "saveState", [])
    assert refused.value.details == {"limit": "savedStates", "value": 2, "flag": "--limit savedStates=N"}
    ops.call("scene", "forgetState", [first])
    assert ops.call("scene", "saveState", []) == "state-3"
    with pytest.raises(UnknownObject):
        ops.call("scene", "restoreState", [first])
