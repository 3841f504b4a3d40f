"""The collision world: shapes shared, and a rebuild into a fresh client."""

from server.core.model import part_figures
from server.core.physics.bullet_parts import GROUND

IDENTITY = (0.0, 0.0, 0.0, 1.0)
CUBE = {"kind": "box", "size": [1, 1, 1]}
HULL = {"kind": "convex", "points": part_figures.extrude([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5),
                                                      (-0.5, 0.5)], 1.0)}


def test_bodies_of_one_geometry_share_a_shape_and_a_rebuild_keeps_them(world):
    for k in range(50):
        world.add(f"b{k}", CUBE, ((3 * k, 0.4, 0), IDENTITY))
    world.add("h", HULL, ((0, 5, 0), IDENTITY))
    assert len(world._shapes) == 2
    world.remove("b0")
    world.rebuild()
    assert len(world) == 50 and "b0" not in world and world.rebuilds == 1
    assert world.parts.touching("b7", GROUND) and world.parts.pose("h")[0] == (0, 5, 0)


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
    assert world.parts.touching("b17", GROUND) and "b3" not in world
