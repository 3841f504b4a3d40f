"""Pictures of a physics world: every part drawn in its colour where the world has it,
hulls included (PyBullet's renderer draws no shape made from points by itself)."""

from __future__ import annotations

import numpy as np
import pytest

from server.core.physics.bullet import pybullet
from server.core.physics.engine import PhysicsWorld
from server.core.physics.picture_world import PictureWorld
from server.core.kit.errors import OutOfRange

RED, BLUE = np.array([255, 0, 0]), np.array([0, 0, 255])
WEDGE = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [1, 0, 1]]


def share_of(pixels: np.ndarray, colour: np.ndarray, columns: slice = slice(None)) -> float:
    """How much of the picture (those columns) is near ``colour`` (shading darkens it)."""
    part = pixels[:, columns].astype(int)
    near = (np.abs(part - colour * part.max(axis=2, keepdims=True) / 255).sum(axis=2) < 60) & \
        (part.max(axis=2) > 60)
    return float(near.mean())


@pytest.fixture
def worlds():
    world, drawn = PhysicsWorld(), PictureWorld(pybullet)
    world.add("box", {"kind": "box", "size": [1, 1, 1], "color": "red"}, ((-1.5, 0.5, 0), (0, 0, 0, 1)))
    world.add("hull", {"kind": "convex", "points": WEDGE, "color": 0x0000FF}, ((1, 0, 0), (0, 0, 0, 1)))
    yield world, drawn
    drawn.close()
    world.close()


def test_parts_are_drawn_in_their_colours_where_they_are_hulls_too(worlds):
    world, drawn = worlds
    pixels = drawn.draw(world, (0, 2, 8), (0, 0.5, 0), 160, 120)
    assert pixels.shape == (120, 160, 3) and pixels.dtype == np.uint8
    assert share_of(pixels, RED, slice(0, 80)) > 0.02 and share_of(pixels, RED, slice(80, 160)) == 0
    assert share_of(pixels, BLUE, slice(80, 160)) > 0.02 and share_of(pixels, BLUE, slice(0, 80)) == 0


def test_a_moved_part_is_drawn_where_it_went_and_a_removed_one_not_at_all(worlds):
    world, drawn = worlds
    drawn.draw(world, (0, 2, 8), (0, 0.5, 0), 160, 120)
    world.move("box", ((1.5, 3, 0), (0, 0, 0, 1)))  # up and to the right
    world.remove("hull")
    pixels = drawn.draw(world, (0, 2, 8), (0, 0.5, 0), 160, 120)
    assert share_of(pixels, BLUE) == 0
    assert share_of(pixels, RED, slice(0, 80)) == 0 and share_of(pixels, RED, slice(80, 160)) > 0.02


def test_a_picture_too_small_or_too_large_is_refused(worlds):
    world, drawn = worlds
    with pytest.raises(OutOfRange, match="width is 16-1024 pixels, not 4000"):
        drawn.draw(world, (0, 2, 8), (0, 0, 0), 4000, 120)
    with pytest.raises(OutOfRange, match="height is 16-1024 pixels, not 8"):
        drawn.draw(world, (0, 2, 8), (0, 0, 0), 160, 8)
