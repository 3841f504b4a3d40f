"""Free bodies made or put inside others in dynamic mode go to the nearest clear spot."""

import itertools
import math

import pytest

from server.core.model.motor import MotorZ
from server.core.model.parts import Ball, Box, EdgedFinger
from server.core.model.robot import Robot


def deepest_overlap(scene, ids):
    """How deep the most overlapping pair of these parts is inside each other (m)."""
    engine = scene.bodies.physics
    deepest = 0.0
    for a, b in itertools.combinations(ids, 2):
        (pa, _), (pb, _) = engine.parts.pose(a), engine.parts.pose(b)
        radius_sum = scene.nodes[a].radius + scene.nodes[b].radius
        deepest = max(deepest, radius_sum - math.dist(pa, pb))
    return deepest


def test_a_pile_made_in_one_spot_becomes_a_heap_side_by_side_and_keeps_ticking(scene):
    # 300 balls made at one point: Bullet's first step took minutes (its multibody solver
    # grows its arrays a contact at a time) and their 45 000 pairs gigabytes
    scene.set_physics("dynamic")
    with scene.journal.transaction():
        for i in range(300):
            Ball(scene, f"b{i}", 0.2).set_position((0, 2, 0))
    ticks = 0
    while len(scene.bodies) < 300:  # built over a few ticks (build_stages)
        scene.tick(1 / 60)
        ticks += 1
        assert ticks < 60
    ids = [f"b{i}" for i in range(300)]
    assert deepest_overlap(scene, ids) < 0.2 * 0.25
    heights = [scene.bodies.physics.parts.pose(i)[0][1] for i in ids]
    assert min(heights) > 0.0 and max(heights) < 2 + 11 * 0.41  # the nearest spots, not far away
    for _ in range(30):
        scene.tick(1 / 60)
    assert scene.nodes["b299"].position != (0, 2, 0)  # the scene took where Bullet put it
    assert scene.bodies.physics.cleared >= 299


def test_a_body_put_where_nothing_is_or_only_touching_stays_where_it_was_put(scene):
    scene.set_physics("dynamic")
    Box(scene, "floor", 10, 1, 10).set_position((0, 0.5, 0))
    scene.nodes["floor"].set_static()
    Ball(scene, "alone", 0.5).set_position((5, 3, 5))
    Ball(scene, "shallow", 0.5).set_position((5, 3.95, 5))  # 5 cm into "alone": the solver's
    scene.tick(1 / 60)
    engine = scene.bodies.physics
    assert engine.parts.pose("alone")[0][0] == pytest.approx(5) and engine.parts.pose("alone")[0][2] == pytest.approx(5)
    assert engine.parts.pose("shallow")[0][0] == pytest.approx(5) and engine.parts.pose("shallow")[0][2] == pytest.approx(5)
    assert engine.cleared == 0


def test_a_ball_a_script_puts_inside_another_is_moved_out_but_not_out_of_a_hand(scene):
    scene.set_physics("dynamic")
    first = Ball(scene, "first", 0.5)
    first.set_position((0, 3, 0))
    second = Ball(scene, "second", 0.5)
    second.set_position((4, 3, 0))
    robot = Robot(scene, "r")
    motor = MotorZ(scene, "m", -1, 1)
    finger = EdgedFinger(scene, "f")
    robot.attach_chain(motor, finger)
    robot.set_position((-4, 3, 0))
    scene.tick(1 / 60)
    second.set_position((0, 3, 0))  # into "first"
    scene.tick(1 / 60)
    assert deepest_overlap(scene, ["first", "second"]) < 0.5 * 0.25
    finger_at = scene.bodies.physics.parts.pose("f")[0]
    third = Ball(scene, "third", 0.3)
    third.set_position(finger_at)  # a hand closes on what it is given: left to the solver
    scene.tick(1 / 60)
    assert math.dist(scene.bodies.physics.parts.pose("third")[0], finger_at) < 0.3
