"""A robot as one GLB: it opens in trimesh with the robot's bounds, a node per link where
the link is, coloured as the viewer colours it."""

import io

import numpy as np
import pytest
import trimesh
from scipy.spatial.transform import Rotation

from server.core.model.hands import EdgedHand, RoundHand
from server.core.model.motor import Slider
from server.core.model.parts import Box
from server.core.model.robot import Robot
from server.core.physics.assets import BUNDLED_DIR
from server.core.protocol.robot_files import robot_glb
from tests.server.core.physics.test_urdf_file import HANDS, _posed


@pytest.mark.parametrize("kind", HANDS)
def test_a_hands_glb_opens_in_trimesh_with_the_hands_bounds(scene, kind):
    hand = _posed(scene, kind)
    opened = trimesh.load(io.BytesIO(robot_glb(scene, "h")), file_type="glb")
    parts = [p for p in hand.get_parts() if p.physical]
    assert set(opened.graph.nodes_geometry) == {p.id for p in parts}
    corners = np.concatenate([_drawn_corners(p) for p in parts])
    metres = np.array([corners.min(axis=0), corners.max(axis=0)]) * scene.physics.unit
    assert opened.bounds == pytest.approx(metres, abs=1e-5)
    assert 0.15 < np.ptp(opened.bounds, axis=0).max() < 0.25  # a human hand's size


def _drawn_corners(part):
    """The points a viewer draws a part through, in the world: a hull's corners, or its
    mesh file's vertices placed as the part places them."""
    geometry = part.geometry()
    if geometry["kind"] == "mesh":
        mesh = trimesh.load(BUNDLED_DIR / geometry["url"].rsplit("/", 1)[1], force="mesh")
        points = np.asarray(mesh.vertices) * ([-1, 1, 1] if geometry["mirror"] else 1) + geometry["offset"]
    else:
        points = np.asarray(geometry["points"])
    position, quaternion = part.world_pose()
    return Rotation.from_quat(quaternion).apply(points) + position


def test_the_glb_colours_parts_as_the_viewer_does(scene):
    hand = RoundHand(scene, "h", True)  # its files' blue recoloured grey: [0.3, 0.3, 0.3]
    robot = Robot(scene, "r")
    Box(scene, "b", 1, 1, 1, "steelblue").attach_to_slot(robot)
    palm = trimesh.load(io.BytesIO(robot_glb(scene, "h")), file_type="glb").geometry[hand.get_parts()[0].id]
    colours = {tuple(c) for c in np.asarray(palm.visual.vertex_colors)[:, :3].tolist()}
    assert (76, 76, 76) in colours and (0, 54, 255) not in colours  # 0.3 × 255
    box = trimesh.load(io.BytesIO(robot_glb(scene, "r")), file_type="glb").geometry["b"]
    # CSS colours are sRGB; glTF's (and three.js's) are linear: steelblue is (70, 130, 180)
    assert box.visual.material.name == "steelblue"
    assert tuple(box.visual.material.baseColorFactor[:3]) == (16, 57, 116)


def test_a_robots_glb_is_a_node_per_link_with_local_transforms(scene):
    hand = _posed(scene, EdgedHand)
    opened = trimesh.load(io.BytesIO(robot_glb(scene, "h")), file_type="glb")
    parents = opened.graph.transforms.parents
    palm, spread = hand.get_parts()[0], hand.get_motors()[0]
    finger = next(p for p in hand.get_parts() if p.type_name == "EdgedFinger")  # the thumb's first
    # a link per part, and one where two motors meet (the spread's), each below its parent
    assert [finger.id, parents[finger.id], parents[parents[finger.id]], parents[palm.id]] == \
        [finger.id, f"{spread.id}.link", palm.id, "h"]
    assert parents["h"] == opened.graph.base_frame
    local, _ = opened.graph.get(finger.id, f"{spread.id}.link")
    world, _ = opened.graph.get(finger.id)
    assert world[:3, 3] == pytest.approx(np.asarray(finger.world_pose()[0]) * scene.physics.unit, abs=1e-9)
    assert not np.allclose(local, world)  # local transforms, not world poses


def test_a_robot_without_parts_is_a_glb_that_draws_nothing(scene):
    Robot(scene, "r")
    data = robot_glb(scene, "r")  # trimesh's export refused it: a 400 'internal' over REST
    assert data[:4] == b"glTF"
    loaded = trimesh.load(io.BytesIO(data), file_type="glb")
    assert isinstance(loaded, trimesh.Scene) and not loaded.geometry


def test_a_sliders_glb_node_sits_where_it_slid(scene):
    robot, slider = Robot(scene, "r"), Slider(scene, "s", [0.0, 0.6, 0.8], 0, 2, 0)
    Box(scene, "b", 0.5, 0.5, 0.5).attach_to_slot(slider)
    robot.attach_chain(slider)
    robot.set_position((1.0, 2.0, 0.0))
    slider.set_angle(1.5)
    opened = trimesh.load(io.BytesIO(robot_glb(scene, "r")), file_type="glb")
    world, _ = opened.graph.get("b")
    assert world[:3, 3] == pytest.approx(np.asarray((1.0, 2.9, 1.2)) * scene.physics.unit, abs=1e-9)
