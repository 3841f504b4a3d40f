"""What presses on parts: told when it changes, once more (as 0) when it ends, and kept as
told for a newcomer's snapshot."""

import pytest

from server.core.model.parts import Box
from server.core.scene.part_forces import PartForces


def test_a_force_is_told_when_it_changes_and_as_nothing_when_it_ends(scene):
    box = Box(scene, "b", 1, 1, 1)
    box.set_position((0, 0.6, 0))
    mine = PartForces(scene.bodies.physics.parts)
    assert mine.changed() == {} and mine.peak() == 0.0  # kinematic mode: nothing presses
    scene.set_physics("dynamic")
    for _ in range(120):  # it lands and lies on the ground
        scene.tick(1 / 60)
    weight = mine.on(box)
    assert weight > 0 and mine.peak() == weight
    pressed = {"b": round(weight, 3), "ground": round(weight, 3)}  # (the ground is pressed too)
    assert mine.changed() == pressed == mine.told()
    assert mine.changed() == {}  # nothing changed since: nothing to tell
    box.set_position((0, 5, 0))  # lifted: nothing presses on it
    scene.tick(1 / 60)
    assert mine.changed() == {"b": 0.0, "ground": 0.0}
    assert mine.told() == {} and mine.on(box) == 0.0 and mine.on(None) == 0.0
    assert mine.peak() == pytest.approx(0.0)
