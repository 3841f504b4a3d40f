"""Links of one robot that overlap where it is built never meet each other in dynamic mode;
the others still do; a robot of many overlapping links meets nothing of its own."""

from __future__ import annotations

from typing import Any

import pytest

from server.core.physics.bullet import pybullet
from server.core.physics.self_contacts import exclude, overlapping_pairs
from server.core.protocol.operations import Operations
from server.core.scene.scene import Scene


@pytest.fixture
def client() -> Any:
    number = pybullet.connect(pybullet.DIRECT)
    yield number
    pybullet.disconnect(physicsClientId=number)


def _chain(client: int, places: list[float]) -> int:
    """A base box and one box link each, fixed to the base at ``x = place``."""
    shape = pybullet.createCollisionShape(pybullet.GEOM_BOX, halfExtents=[0.1] * 3,
                                          physicsClientId=client)
    count = len(places)
    return pybullet.createMultiBody(
        1, shape, basePosition=[0, 0, 5], linkMasses=[1] * count,
        linkCollisionShapeIndices=[shape] * count, linkVisualShapeIndices=[-1] * count,
        linkPositions=[[x, 0, 0] for x in places], linkOrientations=[[0, 0, 0, 1]] * count,
        linkInertialFramePositions=[[0, 0, 0]] * count,
        linkInertialFrameOrientations=[[0, 0, 0, 1]] * count, linkParentIndices=[0] * count,
        linkJointTypes=[pybullet.JOINT_FIXED] * count, linkJointAxis=[[0, 0, 1]] * count,
        flags=pybullet.URDF_USE_SELF_COLLISION | pybullet.URDF_USE_SELF_COLLISION_EXCLUDE_ALL_PARENTS,
        physicsClientId=client)


def test_overlapping_siblings_are_found_and_parents_and_neighbours_apart_are_not(client):
    # links 0 and 1 sit in one place; link 2 touches link 1 face to face; link 3 is apart;
    # every link overlaps the base, its parent (Bullet leaves parents out already)
    body = _chain(client, [1.0, 1.05, 1.25, 3.0])
    assert overlapping_pairs(pybullet, client, body, [-1, -1, -1, -1]) == [(0, 1)]


def test_an_excluded_pair_makes_no_contact_and_the_others_still_do(client):
    body = _chain(client, [1.0, 1.05, 1.15])  # 0-1 deep, 1-2 shallow (1 mm), 0-2 touching
    pairs = overlapping_pairs(pybullet, client, body, [-1, -1, -1])
    assert (0, 1) in pairs
    exclude(pybullet, client, body, [(0, 1)])
    pybullet.performCollisionDetection(physicsClientId=client)
    touching = {tuple(sorted((c[3], c[4]))) for c in
                pybullet.getContactPoints(body, body, physicsClientId=client)}
    assert (0, 1) not in touching
    assert touching - {(0, 1)}, "the pairs left on still meet"


def test_a_robot_of_parts_heaped_on_one_slot_ticks_without_meeting_itself():
    """A robot of 60 parts on the slots of a few (112 links in the fuzzer's case) had
    thousands of contacts with itself in dynamic mode: one step took 5-22 s."""
    scene = Scene("heap")
    try:
        ops = Operations(scene, "c1")
        ops.create("c1.r", "Robot", [])
        ops.create("c1.0", "Box", [])
        ops.call("c1.r", "attachChain", [{"ref": "c1.0"}])
        for k in range(1, 60):
            ops.create(f"c1.{k}", "MotorZ" if k % 2 else "Box", [-1, 1] if k % 2 else [])
            ops.call(f"c1.{k}", "attachToSlot", [{"ref": f"c1.{(k - 1) // 4 * 4}"}, 0])
        ops.call("scene", "setPhysics", ["dynamic"])
        for _ in range(3):
            scene.tick(1 / 60)
        world = scene.bodies.physics
        assert len(world.tree("c1.r").links) >= 30
        own = [c for c in pybullet.getContactPoints(physicsClientId=world.client) if c[1] == c[2]]
        assert own == []
    finally:
        scene.close()
