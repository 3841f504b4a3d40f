"""The transform tree: walking it, how deep it may grow, poses under scaled parents."""

import dataclasses

import pytest

from server.core.kit.limits import DEFAULT
from server.core.model.node import Node, Slot
from server.core.model.parts import Part
from server.core.scene.scene import Scene
from server.core.kit.errors import LimitExceeded


def test_walk_is_depth_first_pre_order_as_threejs_traverse(scene):
    root, a, b, a1 = (Part(scene, n) for n in ("root", "a", "b", "a1"))
    a.attach_to_slot(root)
    b.attach_to_slot(root)
    a1.attach_to_slot(a)
    assert [n.id for n in root.walk()] == ["root", "a", "a1", "b"]
    assert a1.root() is root and root.is_ancestor_of(a1) and not a.is_ancestor_of(b)


def test_a_tree_deeper_than_the_limit_is_refused_naming_the_limit():
    scene = Scene("deep", dataclasses.replace(DEFAULT, tree_depth=3))
    try:
        chain = [Part(scene, f"p{k}") for k in range(4)]
        chain[1].attach_to_slot(chain[0])
        chain[2].attach_to_slot(chain[1])
        with pytest.raises(LimitExceeded) as refused:
            chain[3].attach_to_slot(chain[2])
        assert refused.value.details["limit"] == "treeDepth" and "at most 3" in refused.value.message
        assert chain[3].parent is None
    finally:
        scene.close()


def test_a_parents_scale_stretches_where_its_children_sit(scene):
    parent, child = Node(scene, "n"), Slot(scene, "s", (1, 0, 0))
    parent.add_slot_node(child)
    parent.set_position((0, 1, 0))
    parent.set_scale((2, 2, 2))
    assert child.world_pose()[0] == pytest.approx((2, 1, 0))
    assert child.world_scale() == pytest.approx((2, 2, 2))
