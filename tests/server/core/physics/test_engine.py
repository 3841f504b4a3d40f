"""The collision world: exact pair measures between padded Bullet shapes."""

import pytest

from server.core.model import part_figures
from server.core.physics.engine import GROUND, PhysicsWorld

IDENTITY = (0.0, 0.0, 0.0, 1.0)
CUBE = {"kind": "box", "size": [1, 1, 1]}
HULL = {"kind": "convex", "points": part_figures.extrude([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5),
                                                      (-0.5, 0.5)], 1.0)}


@pytest.fixture
def world():
    w = PhysicsWorld()
    yield w
    w.close()


@pytest.mark.parametrize("shape", [CUBE, HULL])
@pytest.mark.parametrize("gap, touching", [(0.0005, False), (0.0, True), (-0.0005, True)])
def test_contacts_are_those_of_the_exact_shapes(world, shape, gap, touching):
    world.add("a", HULL, ((0, 5, 0), IDENTITY))
    world.add("b", shape, ((1 + gap, 5, 0), IDENTITY))
    assert world.touching("a", "b") is touching and world.touching("b", "a") is touching


def test_the_ground_is_measured_like_a_body(world):
    world.add("hull", HULL, ((0, 0.5005, 0), IDENTITY))
    world.add("ball", {"kind": "sphere", "radius": 0.5}, ((3, 0.4995, 0), IDENTITY))
    assert not world.touching("hull", GROUND) and world.touching("ball", GROUND)


def test_bodies_of_one_geometry_share_a_shape_and_a_rebuild_keeps_them(world):
    for k in range(50):
        world.add(f"b{k}", CUBE, ((3 * k, 0.4, 0), IDENTITY))
    world.add("h", HULL, ((0, 5, 0), IDENTITY))
    assert len(world._shapes) == 2
    world.remove("b0")
    world.rebuild()
    assert len(world) == 50 and "b0" not in world and world.rebuilds == 1
    assert world.touching("b7", GROUND) and world.pose("h")[0] == (0, 5, 0)


def test_a_rebuild_empties_its_client_of_what_was_removed(world):
    import pybullet
    client = world.client
    for k in range(20):
        world.add(f"b{k}", CUBE, ((3 * k, 0.4, 0), IDENTITY))
    for k in range(15):
        world.remove(f"b{k}")
    world.rebuild()
    # the same client, holding only the ground and the five left (Bullet's own count)
    assert world.client == client and pybullet.getNumBodies(physicsClientId=client) == 6
    assert world.touching("b17", GROUND) and "b3" not in world
