"""SceneMeshes (a page's meshes on the server): each geometry is drawn as given and met by rays
and contacts where it is; scale and visibility of any node."""

import math

import pytest

from server.core.protocol.operations import Operations
from server.core.model.parts import Ball, Box, Part
from server.core.model.robot import Robot
from server.core.model.sensor import Sensor
from server.core.model.page_meshes import SceneMesh
from server.core.kit.errors import LimitExceeded

DOWN = (math.pi, 0, 0)
BOX = {"kind": "box", "size": [2, 0.5, 2]}


def down_sensor(scene, height, x=0.0, name="s"):
    sensor = Sensor(scene, name)
    sensor.set_position((x, height, 0))
    sensor.set_rotation(*DOWN)
    return sensor


def shape(scene, geometry, at=(0, 0, 0), name="c1.1", color="red"):
    made = SceneMesh(scene, name, geometry, color)
    made.set_position(at)
    return made


# a 2 × 2 square at y = 1, facing up (counter-clockwise seen from above)
SQUARE = {"kind": "triangles", "vertices": [-1, 1, -1, -1, 1, 1, 1, 1, 1, 1, 1, -1],
          "indices": [0, 1, 2, 0, 2, 3]}


@pytest.mark.parametrize("geometry, top", [
    (BOX, 0.25),
    ({"kind": "sphere", "radius": 0.4}, 0.4),
    ({"kind": "cylinder", "radiusTop": 0.3, "radiusBottom": 0.5, "height": 1.2, "segments": 16}, 0.6),
    ({"kind": "hull", "vertices": [0, 0.7, 0, 1, -0.2, 0, -1, -0.2, 1, -1, -0.2, -1]}, 0.7),
    (SQUARE, 1.0),
])
def test_a_sensor_above_a_shape_reads_the_distance_to_its_top(scene, geometry, top):
    shape(scene, geometry, at=(0, 1, 0))
    assert down_sensor(scene, 3.0).sense_distance() == pytest.approx(3.0 - 1 - top, abs=1e-9)


def test_a_triangle_mesh_is_met_from_its_front_only(scene):
    shape(scene, SQUARE)
    assert down_sensor(scene, 3.0).sense_distance() == pytest.approx(2.0, abs=1e-12)
    below = Sensor(scene, "below")
    below.set_position((0, 0.5, 0))  # looking up at the square's back: the ray passes
    assert below.sense_distance() == math.inf


def test_a_cylinder_is_met_on_its_flat_sides_as_three_js_draws_it(scene):
    shape(scene, {"kind": "cylinder", "radiusTop": 1, "radiusBottom": 1, "height": 2,
                  "segments": 4})  # a square prism with corners at ±Z and ±X
    side = Sensor(scene, "side")
    side.set_position((0, 0, 3))
    side.set_rotation(-math.pi / 2, 0, 0)  # +Y turned to -Z: straight at the corner at +Z
    assert side.sense_distance() == pytest.approx(2.0, abs=1e-9)
    side.set_position((0.5, 0, 3))  # half way along a face from that corner
    assert side.sense_distance() == pytest.approx(2.5, abs=1e-9)


def test_a_hull_keeps_only_its_corners(scene):
    inner = [0.1, 0.1, 0.1, -0.1, 0, 0]
    corners = [1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1]
    made = shape(scene, {"kind": "hull", "vertices": corners + inner})
    assert sorted(map(tuple, made.describe()["geometry"]["points"])) == \
        sorted(tuple(corners[k:k + 3]) for k in range(0, len(corners), 3))


def test_a_shape_is_described_with_its_geometry_and_colour(scene):
    described = shape(scene, {"kind": "sphere", "radius": 0.5}, color=0x3366FF).describe()
    assert described["type"] == "SceneMesh" and described["physical"] is True
    assert described["geometry"] == {"kind": "sphere", "radius": 0.5}
    assert described["color"] == 0x3366FF


def test_set_color_reaches_viewers_as_an_update(scene):
    made = shape(scene, BOX)
    scene.tick(1 / 60)
    made.set_color("blue")
    frame = scene.tick(1 / 60)[-1]
    assert frame["updates"] == {"c1.1": {"color": "blue"}}
    assert made.describe()["color"] == "blue"


def test_shapes_touch_parts_and_the_ground(scene):
    ball = Ball(scene, "ball", 0.5)
    ball.set_position((0, 2, 0))
    shape(scene, BOX, at=(0, 1.5, 0))  # top at 1.75: inside the ball
    assert scene.bodies.touching(ball) == ["c1.1"]
    low = shape(scene, {"kind": "sphere", "radius": 0.2}, at=(5, 0.1, 0), name="c1.2")
    assert scene.bodies.touching(low) == ["ground"]


def test_a_triangle_mesh_touches_by_its_hull(scene):
    shape(scene, SQUARE)
    ball = Ball(scene, "ball", 0.2)
    ball.set_position((0.5, 0.7, 0.5))  # 0.1 below the square
    assert scene.bodies.touching(ball) == []
    ball.set_position((0.5, 0.9, 0.5))  # through it
    assert scene.bodies.touching(ball) == ["c1.1"]


def test_shapes_are_not_among_a_robots_parts(scene):
    robot = Robot(scene, "r")
    box = Box(scene, "b")
    box.attach_to_slot(robot)
    SceneMesh(scene, "c1.1", BOX).attach_to_slot(box)
    assert [p.id for p in robot.get_parts()] == ["b"]


@pytest.mark.parametrize("geometry, words", [
    ("box", "expected a geometry"),
    ({"kind": "torus"}, "expected a geometry"),
    ({"kind": "box"}, "needs size"),
    ({"kind": "box", "size": [1, 1, 1], "radius": 2}, "has no field radius"),
    ({"kind": "box", "size": [1, 0, 1]}, "lies between"),
    ({"kind": "sphere", "radius": "big"}, "finite number"),
    ({"kind": "cylinder", "radiusTop": 0, "radiusBottom": 0, "height": 1, "segments": 8}, "radius of at least"),
    ({"kind": "cylinder", "radiusTop": 1, "radiusBottom": 1, "height": 1, "segments": 2}, "segments"),
    ({"kind": "hull", "vertices": [0, 0, 0, 1, 1]}, "at least 3 vertices"),
    ({"kind": "hull", "vertices": [0, 0, 0, 1, 1, 1, True, 0, 0]}, "expected numbers"),
    ({"kind": "hull", "vertices": [0, 0, 0, 1, 1, 1, 2e9, 0, 0]}, "within"),
    ({"kind": "triangles", "vertices": [0, 0, 0, 1, 0, 0, 0, 1, 0], "indices": [0, 1, 3]}, "from 0 to 2"),
    ({"kind": "triangles", "vertices": [0, 0, 0, 1, 0, 0, 0, 1, 0], "indices": [0, 1]}, "three per"),
    ({"kind": "triangles", "vertices": [0, 0, 0, 1, 0, 0, 0, 1, 0], "indices": [0, 1, 1.5]}, "whole"),
])
def test_a_bad_geometry_is_refused_and_nothing_is_made(scene, geometry, words):
    operations = Operations(scene, "c1")
    with pytest.raises(Exception) as refused:
        operations.create("c1.1", "SceneMesh", [geometry])
    assert words in str(refused.value) and "geometry" in str(refused.value)
    assert "c1.1" not in scene.nodes and len(scene.bodies.physics) == 0


def test_a_geometry_over_the_vertex_limit_is_refused(scene):
    count = scene.limits.shape_vertices + 1
    with pytest.raises(Exception, match="at most"):
        SceneMesh(scene, "c1.1", {"kind": "hull", "vertices": [float(k % 7) for k in range(3 * count)]})
    assert "c1.1" not in scene.nodes


# --- scale ---------------------------------------------------------------------------------

def test_scale_stretches_a_parts_shape_for_rays_and_contacts(scene):
    box = Box(scene, "b", 1, 1, 1)
    box.set_position((0, 1, 0))
    sensor = down_sensor(scene, 3.0)
    assert sensor.sense_distance() == pytest.approx(1.5, abs=1e-12)
    box.set_scale((1, 3, 1))  # top at 2.5
    assert sensor.sense_distance() == pytest.approx(0.5, abs=1e-12)
    assert scene.bodies.touching(box) == ["ground"]  # bottom at -0.5
    box.set_scale((1, 1, 1))
    assert sensor.sense_distance() == pytest.approx(1.5, abs=1e-12)
    assert scene.bodies.touching(box) == []


def test_a_parents_scale_moves_its_children_and_stretches_their_shapes(scene):
    holder = Part(scene, "holder")
    ball = Ball(scene, "ball", 0.25)
    ball.attach_to_slot(holder)
    ball.set_position((2, 0, 0))
    holder.set_scale((2, 2, 2))
    assert ball.world_pose()[0] == (4.0, 0.0, 0.0)
    sensor = down_sensor(scene, 3.0, x=4.0)
    assert sensor.sense_distance() == pytest.approx(2.5, abs=1e-9)  # radius 0.5 now


def test_a_sphere_stretched_one_way_becomes_an_ellipsoid(scene):
    ball = Ball(scene, "ball", 0.5)
    ball.set_position((0, 1, 0))
    ball.set_scale((1, 2, 1))
    assert down_sensor(scene, 3.0).sense_distance() == pytest.approx(1.0, abs=1e-9)


def test_a_mesh_part_is_stretched_for_rays(scene):
    from server.core.model.gltf_parts import RoundFinger
    finger = RoundFinger(scene, "f", "round-finger-8.glb")
    finger.set_rotation(math.pi / 2, 0, 0)  # lying along +Z, its top towards +Y
    sensor = down_sensor(scene, 3.0, x=0.0)
    sensor.set_position((0, 3, 0.4))
    before = sensor.sense_distance()
    finger.set_scale((1, 1, 3))  # three times as thick (its local Z is now up)
    after = sensor.sense_distance()
    assert math.isfinite(before) and 3.0 - after == pytest.approx(3 * (3.0 - before), rel=1e-6)


def test_scale_is_described_and_its_changes_sent(scene):
    box = Box(scene, "b")
    assert box.describe()["scale"] == [1.0, 1.0, 1.0]
    scene.tick(1 / 60)
    box.set_scale((2, 1, 1))
    assert scene.tick(1 / 60)[-1]["updates"] == {"b": {"scale": [2.0, 1.0, 1.0]}}
    assert box.describe()["scale"] == [2.0, 1.0, 1.0]


# --- visibility ----------------------------------------------------------------------------

def test_a_hidden_part_is_still_met_by_rays_as_in_1_0(scene):
    box = Box(scene, "b")
    box.set_position((0, 1, 0))
    box.set_visible(False)
    assert box.describe()["visible"] is False
    assert down_sensor(scene, 3.0).sense_distance() == pytest.approx(1.5, abs=1e-12)


def test_a_hidden_robot_is_out_of_the_scene(scene):
    robot = Robot(scene, "r")
    box = Box(scene, "b")
    box.attach_to_slot(robot)
    robot.set_position((0, 1, 0))
    sensor = down_sensor(scene, 3.0)
    assert sensor.sense_distance() == pytest.approx(1.5, abs=1e-12)
    robot.set_visible(False)
    assert sensor.sense_distance() == pytest.approx(3.0, abs=1e-12)


# --- setTransforms -------------------------------------------------------------------------

def test_set_transforms_places_many_objects_in_one_call(scene):
    operations = Operations(scene, "c1")
    for k in range(3):
        operations.create(f"c1.{k}", "SceneMesh", [{"kind": "sphere", "radius": 0.1}])
    half = math.sqrt(0.5)
    operations.call("scene", "setTransforms", [{
        "c1.0": [1, 2, 3, 0, 0, 0, 1], "c1.1": [0, 1, 0, 0, 0, 1, 1],
        "c1.2": [0, 0, 0, 0, 0, 0, 2, 2, 2, 2]}])
    assert scene.nodes["c1.0"].position == (1.0, 2.0, 3.0)
    assert scene.nodes["c1.1"].quaternion == pytest.approx((0, 0, half, half))
    assert scene.nodes["c1.2"].scale == (2.0, 2.0, 2.0)
    assert scene.nodes["c1.2"].quaternion == (0.0, 0.0, 0.0, 1.0)


def test_set_transforms_over_the_limit_is_refused(scene):
    operations = Operations(scene, "c1")
    operations.create("c1.0", "Ball", [])
    limit = scene.limits.transforms_per_call
    with pytest.raises(LimitExceeded, match="at most"):
        scene.set_transforms([(scene.nodes["c1.0"], (0, 0, 0), (0, 0, 0, 1), None)] * (limit + 1))


def test_a_flat_hull_is_a_shape_rays_meet(scene):
    # four points in the plane y = 1 (a page's PlaneGeometry sent as a hull)
    shape(scene, {"kind": "hull", "vertices": [-1, 1, -1, 1, 1, -1, 1, 1, 1, -1, 1, 1]})
    assert down_sensor(scene, 3.0).sense_distance() == pytest.approx(2.0, abs=1e-6)
