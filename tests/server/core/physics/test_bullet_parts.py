"""Parts as Bullet holds them: exact pair measures between padded Bullet shapes, and
contacts named by part whatever body ids Bullet hands out again."""

import pytest

from server.core.model import part_figures
from server.core.physics.bullet_parts import GROUND

IDENTITY = (0.0, 0.0, 0.0, 1.0)
CUBE = {"kind": "box", "size": [1, 1, 1]}
HULL = {"kind": "convex", "points": part_figures.extrude([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5),
                                                      (-0.5, 0.5)], 1.0)}


@pytest.mark.parametrize("shape", [CUBE, HULL])
@pytest.mark.parametrize("gap, touching", [(0.0005, False), (0.0, True), (-0.0005, True)])
def test_contacts_are_those_of_the_exact_shapes(world, shape, gap, touching):
    world.add("a", HULL, ((0, 5, 0), IDENTITY))
    world.add("b", shape, ((1 + gap, 5, 0), IDENTITY))
    assert world.parts.touching("a", "b") is touching and world.parts.touching("b", "a") is touching


def test_the_ground_is_measured_like_a_body(world):
    world.add("hull", HULL, ((0, 0.5005, 0), IDENTITY))
    world.add("ball", {"kind": "sphere", "radius": 0.5}, ((3, 0.4995, 0), IDENTITY))
    assert not world.parts.touching("hull", GROUND) and world.parts.touching("ball", GROUND)


def test_contacts_name_the_parts_of_bodies_whose_ids_bullet_gave_again(world):
    def add(key, geometry, x):
        world.add(key, geometry, ((x, 5, 0), IDENTITY))
        world.parts.crowd(key, False)  # (new parts are in a crowd until the tracker knows)
    add("a", CUBE, 0)
    add("b", CUBE, 1)
    assert set(world.parts.detect()) == {("a", "b")}
    world.remove("b")
    add("c", HULL, -1)  # Bullet gives it b's body id
    assert set(world.parts.detect()) == {("a", "c")}
    assert "b" not in world.parts and "c" in world.parts and len(world.parts) == 2
    assert world.parts.pose("c") == ((-1.0, 5.0, 0.0), IDENTITY)
