"""The registry: ids new to the scene, quotas per scene and per owner, deleted ids told apart."""

import dataclasses

import pytest

from server.core.kit.limits import DEFAULT
from server.core.model.motor import MotorZ
from server.core.model.parts import Ball, Box
from server.core.model.robot import Robot
from server.core.scene.scene import Scene
from server.core.kit.errors import LimitExceeded, UnknownObject


@pytest.fixture
def small():
    scene = Scene("small", dataclasses.replace(DEFAULT, scene_objects=4, client_objects=3,
                                               scene_bodies=2))
    yield scene
    scene.close()


def test_each_quota_is_named_with_its_value_and_refuses_before_anything_is_made(small):
    Box(small, "c1.1")
    Box(small, "c1.2")
    with pytest.raises(LimitExceeded) as bodies:
        Ball(small, "c2.1")
    assert (bodies.value.details["limit"], bodies.value.details["value"]) == ("sceneBodies", 2)
    Robot(small, "c1.3")
    with pytest.raises(LimitExceeded) as own:
        Robot(small, "c1.4")
    assert (own.value.details["limit"], own.value.details["value"]) == ("clientObjects", 3)
    Robot(small, "c2.2")
    with pytest.raises(LimitExceeded) as whole:
        Robot(small, "c3.1")
    assert (whole.value.details["limit"], whole.value.details["value"]) == ("sceneObjects", 4)
    assert sorted(small.nodes) == ["c1.1", "c1.2", "c1.3", "c2.2"]
    assert small.registry.owned == {"c1": 3, "c2": 1} and small.registry.physical == 2


def test_a_deleted_object_is_told_apart_from_one_never_made(scene):
    scene.delete(Box(scene, "c1.1"))
    with pytest.raises(UnknownObject, match="c1.1 was deleted from scene test"):
        scene.get("c1.1")
    with pytest.raises(UnknownObject, match="c1.9 is not in scene test"):
        scene.get("c1.9")


def test_an_undone_deletion_keeps_the_order_things_were_made_in(scene):
    first, second = Box(scene, "c1.1"), Ball(scene, "c1.2")
    with pytest.raises(RuntimeError), scene.journal.transaction():
        scene.delete(first)
        raise RuntimeError("undo")
    assert list(scene.nodes) == ["c1.2", "c1.1"]  # the dict lost the order …
    assert scene.in_order_made() == [first, second]  # … the serials did not
    assert scene.registry.owned == {"c1": 2}


def test_left_behind_lists_own_top_level_objects_not_kept(scene):
    robot = Robot(scene, "c1.1")
    robot.attach_chain(MotorZ(scene, "c1.2"))
    Box(scene, "c1.3").keep()
    Ball(scene, "c2.1")
    assert [n.id for n in scene.registry.left_behind("c1")] == ["c1.1", "c1.2"]
