"""Exact rays: front faces of spheres, boxes, hulls and meshes, and the ground from above."""

import math

import numpy as np
import pytest

from server.core.kit import math3d
from server.core.physics.assets import AssetLibrary
from server.core.physics.raycast import RayTargets

IDENTITY = (0.0, 0.0, 0.0, 1.0)
DOWN, UP = (0, -1, 0), (0, 1, 0)
FAR = 1000.0


@pytest.fixture
def targets():
    return RayTargets(AssetLibrary())


def first(targets, origin, direction=DOWN, limit=0.0):
    [hit] = targets.first_hits(origin, direction, [limit], FAR)
    return hit


def test_the_ground_is_met_from_above_only(targets):
    assert first(targets, (3, 2.5, -1)) == ("ground", 2.5)
    assert first(targets, (0, 0, 0)) == ("ground", 0.0)  # lying on it
    assert first(targets, (0, -1, 0), UP) == ("", math.inf)
    assert first(targets, (0, 1, 0), (1, 0, 0)) == ("", math.inf)


def test_a_sphere_is_met_where_the_ray_enters_it(targets):
    targets.add("ball", {"kind": "sphere", "radius": 0.5}, ((0, 2, 0), IDENTITY))
    assert first(targets, (0, 5, 0)) == ("ball", 2.5)
    slant = (0.3, 5, 0)  # enters where y = 2 + sqrt(0.25 - 0.09) = 2.4
    assert first(targets, slant) == ("ball", pytest.approx(2.6, abs=1e-12))
    assert first(targets, (0, 2.2, 0)) == ("ground", 2.2)  # from inside: never the ball
    assert first(targets, (0, 1, 0), UP) == ("ball", 0.5)
    assert first(targets, (0, 3, 0), UP) == ("", math.inf)  # behind the ray
    assert first(targets, (0.6, 5, 0)) == ("ground", 5)  # passes by


def test_a_turned_box_is_met_on_its_edge(targets):
    turned = math3d.axis_angle("z", math.pi / 4)
    targets.add("box", {"kind": "box", "size": [1, 1, 1]}, ((0, 3, 0), turned))
    assert first(targets, (0, 10, 0)) == ("box", pytest.approx(7 - math.sqrt(0.5), abs=1e-12))
    assert first(targets, (0.2, 10, 0))[1] == pytest.approx(7 - math.sqrt(0.5) + 0.2, abs=1e-12)


def test_a_hull_is_met_on_its_faces(targets):
    tetra = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    targets.add("t", {"kind": "convex", "points": tetra}, ((0, 1, 0), IDENTITY))
    # the slanted face x + y + z = 1 (in the part) above (0.2, 0.3): y = 0.5
    assert first(targets, (0.2, 4, 0.3)) == ("t", pytest.approx(4 - 1.5, abs=1e-12))
    assert first(targets, (0.2, 1.4, 0.3)) == ("ground", 1.4)  # starts inside


def test_limits_skip_what_is_nearer_and_rays_see_beyond(targets):
    targets.add("low", {"kind": "box", "size": [1, 0.1, 1]}, ((0, 1, 0), IDENTITY))
    hits = targets.first_hits((0, 1.08, 0), DOWN, [0.0, 0.05, 0.5], FAR)
    assert hits == [("low", pytest.approx(0.03)), ("ground", 1.08), ("ground", 1.08)]
    assert targets.first_hits((0, 1.08, 0), DOWN, [0.03], FAR) == [("low", pytest.approx(0.03))]
    assert targets.first_hits((0, 1.08, 0), DOWN, [0.0], 0.02) == [("", math.inf)]


def test_a_mesh_is_met_on_its_triangles_and_mirrored_like_its_part(targets):
    library = AssetLibrary()
    finger = library.mesh("round-tip.glb")
    placed = finger.vertices + [0, 0.25, 0]
    geometry = {"kind": "mesh", "url": finger.url, "offset": [0, 0.25, 0], "mirror": False}
    targets.add("tip", geometry, ((0, 1, 0), IDENTITY))
    rng = np.random.default_rng(7)
    for _ in range(30):
        start = np.array([-1.0, rng.uniform(0.9, 1.6), rng.uniform(-0.2, 0.2)])  # beside it
        direction = np.array([1.0, rng.uniform(-0.3, 0.3), rng.uniform(-0.1, 0.1)])
        direction /= np.linalg.norm(direction)
        expected = _reference_first(placed, finger.triangles, start - [0, 1, 0], direction)
        key, distance = first(targets, start, tuple(direction))
        if expected is None:
            assert key != "tip"
        else:
            assert key == "tip" and distance == pytest.approx(expected, abs=1e-9)


def _reference_first(vertices, triangles, origin, direction):
    """Plane crossings kept when inside all three edges: another way than the server's."""
    best = None
    for a, b, c in vertices[triangles]:
        normal = np.cross(b - a, c - a)
        if normal @ direction >= 0:
            continue
        t = normal @ (a - origin) / (normal @ direction)
        point = origin + t * direction
        inside = all(np.cross(q - p, point - p) @ normal >= 0 for p, q in ((a, b), (b, c), (c, a)))
        if inside and t >= 0 and (best is None or t < best):
            best = t
    return best


def test_a_mirrored_mesh_is_met_where_its_mirror_image_is(targets):
    thumb = AssetLibrary().mesh("anthro-thumb.glb")  # not symmetric in X
    for name, mirror, x in (("left", False, -3.0), ("right", True, 3.0)):
        geometry = {"kind": "mesh", "url": thumb.url, "offset": [0, 0, 0], "mirror": mirror}
        targets.add(name, geometry, ((x, 1, 0), IDENTITY))
    for dx in (-0.1, -0.05, 0.0, 0.05, 0.1):
        left = first(targets, (-3 + dx, 3, 0.05))
        right = first(targets, (3 - dx, 3, 0.05))
        assert left[0] == "left" and right[0] == "right"
        assert right[1] == pytest.approx(left[1], abs=1e-12)


def test_a_ray_from_inside_a_mesh_does_not_see_it(targets):
    palm = AssetLibrary().mesh("round-palm.glb")
    geometry = {"kind": "mesh", "url": palm.url, "offset": [0, 0.7, 0], "mirror": False}
    targets.add("palm", geometry, ((0, 1, 0), IDENTITY))
    assert first(targets, (0, 1.5, 0)) == ("ground", 1.5)
    assert first(targets, (0, 1.5, 0), (0, 0, 1)) == ("", math.inf)


def test_the_nearest_of_many_and_after_removals(targets):
    rng = np.random.default_rng(3)
    balls = {f"b{k}": (rng.uniform(-3, 3), rng.uniform(1, 9), rng.uniform(0.1, 0.6)) for k in range(200)}
    for key, (x, y, r) in balls.items():
        targets.add(key, {"kind": "sphere", "radius": r}, ((x, y, 0), IDENTITY))
    for key in list(balls)[::3]:
        targets.remove(key)
        del balls[key]
    assert len(targets) == len(balls)
    for x in np.linspace(-3, 3, 25):
        tops = [(10 - y - math.sqrt(r * r - (x - bx) ** 2), key)
                for key, (bx, y, r) in balls.items() if abs(x - bx) < r]
        distance, key = min(tops, default=(10.0, "ground"))
        assert first(targets, (x, 10, 0)) == (key, pytest.approx(distance, abs=1e-12))


def test_moving_a_shape_moves_what_rays_meet(targets):
    targets.add("b", {"kind": "box", "size": [1, 1, 1]}, ((0, 2, 0), IDENTITY))
    targets.move("b", ((5, 2, 0), IDENTITY))
    assert first(targets, (0, 4, 0)) == ("ground", 4)
    assert first(targets, (5, 4, 0)) == ("b", 1.5)


def test_trees_placed_at_once_and_shapes_moved_one_by_one_the_later_wins(targets):
    box = {"kind": "box", "size": [1, 1, 1]}
    targets.add("a", box, ((0, 2, 0), IDENTITY))
    targets.add("b", box, ((3, 2, 0), IDENTITY))
    targets.move("a", ((9, 2, 0), IDENTITY))
    targets.place_trees([(("a", "b"), np.array([[0, 3, 0, *IDENTITY], [3, 4, 0, *IDENTITY]], float))])
    assert first(targets, (0, 9, 0)) == ("a", 5.5)  # placed with its tree after it was moved
    assert first(targets, (3, 9, 0)) == ("b", 4.5)
    targets.move("b", ((6, 2, 0), IDENTITY))
    assert first(targets, (3, 9, 0)) == ("ground", 9)  # moved after its tree was placed
    targets.place_trees([(("b",), np.array([[6, 2, 0, *IDENTITY]], float))])
    targets.remove("a")  # b takes a's row: the tree's rows are looked up again
    targets.place_trees([(("b",), np.array([[0, 2, 0, *IDENTITY]], float))])
    assert first(targets, (0, 9, 0)) == ("b", 6.5)
    assert first(targets, (6, 9, 0)) == ("ground", 9)


def test_shapes_added_and_removed_between_casts_are_met_at_their_own_size(targets):
    ball = {"kind": "sphere", "radius": 0.1}
    targets.add("small", ball, ((0, 2, 0), IDENTITY))
    assert first(targets, (0.5, 9, 0)) == ("ground", 9)  # beside the small ball
    targets.add("big", {**ball, "radius": 1.0}, ((0, 2, 0), IDENTITY))
    assert first(targets, (0.5, 9, 0)) == ("big", pytest.approx(7 - math.sqrt(0.75), abs=1e-12))
    targets.remove("small")  # the big ball takes its row
    assert first(targets, (0.5, 9, 0)) == ("big", pytest.approx(7 - math.sqrt(0.75), abs=1e-12))
    targets.remove("big")
    targets.add("small", ball, ((0.5, 2, 0), IDENTITY))
    assert first(targets, (0.5, 9, 0)) == ("small", pytest.approx(6.9, abs=1e-12))
