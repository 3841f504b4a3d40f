"""Where the nodes that parts carry are: a part's frame composed with each node's offset
from it, for many nodes at once; a node the tree must pose (under a stretched part) is
posed by its tree."""

import numpy as np
import pytest

from server.core.kit import math3d
from server.core.model.parts import Box
from server.core.model.sensor import Sensor
from server.core.scene.carriers import Carriers


def _frames_of(scene):
    """Parts' frames as the ray targets would give them: from the parts' own world poses."""
    def frames(keys):
        poses = [scene.nodes[key].world_pose() for key in keys]
        return (np.array([p for p, _ in poses]),
                np.array([math3d.to_matrix(q) for _, q in poses]))
    return frames


def _built(scene, *parts):
    carriers = Carriers()
    carriers.built([part.id for part in parts], [part.world_scale() for part in parts])
    return carriers


def _assert_at(position, turn, node):
    want_p, want_q = node.world_pose()
    assert position.tolist() == pytest.approx(want_p, abs=1e-12)
    assert turn.ravel().tolist() == pytest.approx(np.ravel(math3d.to_matrix(want_q)).tolist(), abs=1e-12)


def test_nodes_on_parts_are_where_their_parts_frames_and_offsets_put_them(scene):
    box = Box(scene, "b", 1, 1, 1)
    box.set_position((1, 2, 3))
    box.set_rotation(0.3, -0.2, 0.5)
    sensors = []
    for k in range(3):
        sensor = Sensor(scene, f"s{k}")
        sensor.attach_to_slot(box)
        sensor.set_position((0.1 * k, 0.5, 0))
        sensor.set_rotation(0.2 * k, 0, 0.1)
        sensors.append(sensor)
    positions, turns = _built(scene, box).world_frames(sensors, _frames_of(scene))
    for k, sensor in enumerate(sensors):
        _assert_at(positions[k], turns[k], sensor)


def test_a_node_under_a_stretched_part_is_posed_by_its_tree(scene):
    box = Box(scene, "b", 1, 1, 1)
    box.set_scale((1, 2, 1))
    sensor = Sensor(scene, "s")
    sensor.attach_to_slot(box)
    sensor.set_position((0, 0.5, 0))
    asked = []
    frames = _frames_of(scene)
    positions, turns = _built(scene, box).world_frames(
        [sensor], lambda keys: asked.append(list(keys)) or frames(keys))
    _assert_at(positions[0], turns[0], sensor)
    assert asked == []  # no part's frame was used for it


def test_a_part_forgotten_carries_nothing_and_its_nodes_are_posed_by_the_tree(scene):
    box = Box(scene, "b", 1, 1, 1)
    sensor = Sensor(scene, "s")
    sensor.attach_to_slot(box)
    carriers = _built(scene, box)
    asked = []
    frames = _frames_of(scene)
    counting = lambda keys: asked.append(list(keys)) or frames(keys)  # noqa: E731
    carriers.world_frames([sensor], counting)
    assert asked == [["b"]]
    carriers.forget(["b"])
    box.set_position((4, 0, 0))
    positions, turns = carriers.world_frames([sensor], counting)
    assert asked == [["b"]]
    _assert_at(positions[0], turns[0], sensor)


def test_a_watched_sensor_moved_to_another_part_reports_that_parts_contacts(scene):
    low, high = Box(scene, "low", 1, 1, 1), Box(scene, "high", 1, 1, 1)
    low.set_position((0, 0.5, 0))  # on the ground
    high.set_position((3, 5, 0))
    sensor = Sensor(scene, "s")
    sensor.attach_to_slot(low)
    sensor.watch(client="c1")
    scene.tick(1 / 60)
    assert scene.watched_readings()["s"].objects == ("ground",)
    sensor.attach_to_slot(high)  # the hosts kept for the watched set are asked again
    scene.tick(1 / 60)
    assert scene.watched_readings()["s"].objects == ()
    assert scene.bodies.read([sensor])["s"].objects == ()
