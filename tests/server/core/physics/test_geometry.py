"""A page mesh's geometry as data: checked from the wire, and stretched by a scale."""

import pytest

from server.core.physics import geometry
from server.core.kit.errors import BadArguments, WrongType


def checked(value):
    return geometry.check(value, "SceneMesh geometry", max_vertices=100, max_triangles=100)


def test_each_kind_is_kept_as_given_and_a_hull_as_its_corners():
    assert checked({"kind": "box", "size": [1, 2, 3]}) == {"kind": "box", "size": [1, 2, 3]}
    assert checked({"kind": "sphere", "radius": 0.5}) == {"kind": "sphere", "radius": 0.5}
    cube = [x for corner in ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (1, 0, 1),
                             (0, 1, 1), (1, 1, 1), (0.5, 0.5, 0.5)) for x in corner]
    hull = checked({"kind": "hull", "vertices": cube})
    assert hull["kind"] == "convex" and len(hull["points"]) == 8   # the inner point is gone


def test_a_wrong_geometry_names_what_is_wrong():
    with pytest.raises(WrongType, match="expected a geometry"):
        checked({"kind": "torus"})
    with pytest.raises(BadArguments, match="a box geometry has no field radius"):
        checked({"kind": "box", "size": [1, 1, 1], "radius": 2})
    with pytest.raises(BadArguments, match="a sphere geometry needs radius"):
        checked({"kind": "sphere"})


def test_a_cylinder_is_drawn_as_threejs_draws_it():
    points = geometry.cylinder_points({"radiusTop": 1, "radiusBottom": 0, "height": 2, "segments": 4})
    assert points[0] == pytest.approx([0, 1, 1])          # three.js starts at +Z
    assert points[1] == pytest.approx([1, 1, 0], abs=1e-12)
    assert points[-1] == [0.0, -1, 0.0]                   # a cone's tip: one point


def test_scaling_keeps_kinds_rays_and_physics_know():
    assert geometry.scaled({"kind": "sphere", "radius": 1}, (2, 2, 2)) == {"kind": "sphere", "radius": 2}
    assert geometry.scaled({"kind": "box", "size": [1, 1, 1]}, (1, 2, 3))["size"] == [1, 2, 3]
    stretched = geometry.scaled({"kind": "sphere", "radius": 1}, (2, 1, 1))
    assert stretched["kind"] == "convex"
    assert max(p[0] for p in stretched["points"]) == pytest.approx(2)
    flat = geometry.scaled({"kind": "box", "size": [1, 1, 1]}, (0, 1, 1))
    assert flat["size"][0] == geometry.MIN_SCALE          # never nothing (Bullet needs some)
