"""Ray shapes on their own: each shape answers many rays at once, front faces only, per limit."""

import numpy as np
import pytest
import trimesh

from server.core.physics import rayshapes
from server.core.physics.assets import AssetLibrary
from server.core.physics.rayshapes import GROUND_SHAPE, Sphere, Triangles, box, hull, shape_of


def rays(seed: int, count: int) -> tuple[np.ndarray, np.ndarray]:
    """Rays from around the origin aimed near it: about half meet a unit-sized shape."""
    rng = np.random.default_rng(seed)
    origins = rng.uniform(-3, 3, (count, 3))
    directions = rng.uniform(-1, 1, (count, 3)) - origins
    return origins, directions / np.linalg.norm(directions, axis=1, keepdims=True)


def test_a_box_as_planes_and_as_triangles_meets_every_ray_alike():
    size = (1.0, 2.0, 0.5)
    mesh = trimesh.creation.box(size)
    as_triangles = Triangles(np.asarray(mesh.vertices), np.asarray(mesh.faces))
    origins, directions = rays(1, 2000)
    planes = box(size).entries(origins, directions, [0.0, 1.0])
    triangles = as_triangles.entries(origins, directions, [0.0, 1.0])
    assert np.isfinite(planes[:, 0]).sum() > 500  # enough rays meet it to mean something
    np.testing.assert_allclose(planes, triangles, atol=1e-9)


def test_a_hull_meets_rays_by_one_plane_per_face_as_its_triangles_do():
    corners = [(x, y, z) for x in (-0.5, 0.5) for y in (-1, 1) for z in (-0.25, 0.25)]
    tilted = corners + [(0.0, 1.4, 0.0)]  # a roof: faces of one and of two triangles
    for points, faces in ((corners, 6), (tilted, 9)):
        shape, mesh = hull(points), trimesh.convex.convex_hull(np.array(points))
        assert len(shape.offsets) == faces  # qhull gave two triangles per rectangle
        origins, directions = rays(4, 2000)
        as_triangles = Triangles(np.asarray(mesh.vertices), np.asarray(mesh.faces))
        np.testing.assert_allclose(shape.entries(origins, directions, [0.0, 0.5]),
                                   as_triangles.entries(origins, directions, [0.0, 0.5]), atol=1e-9)


def test_a_convex_shape_is_entered_once_so_a_limit_past_the_entry_sees_nothing():
    origin, up = np.array([[0.0, -3.0, 0.0]]), np.array([[0.0, 1.0, 0.0]])
    assert Sphere(1).entries(origin, up, [0.0, 2.0, 2.5]).tolist() == [[2.0, 2.0, np.inf]]
    assert hull([(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]).entries(
        origin, up, [0.0]).tolist() == [[2.0]]


def test_a_ray_from_inside_sees_nothing_and_one_on_a_face_meets_it_at_zero():
    right = np.array([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    inside_and_on = np.array([[0.0, 0.0, 0.0], [-0.5, 0.0, 0.0]])
    for shape in (box((1, 1, 1)), Sphere(0.5)):
        assert shape.entries(inside_and_on, right, [0.0]).tolist() == [[np.inf], [0.0]]


def test_the_ground_is_met_from_above_only():
    origins = np.array([[0.0, 2.0, 0.0], [0.0, 2.0, 0.0], [0.0, -1.0, 0.0]])
    directions = np.array([[0.0, -1.0, 0.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0]])
    assert GROUND_SHAPE.entries(origins, directions, [0.0]).tolist() == [[2.0], [np.inf], [np.inf]]


def test_many_rays_against_a_mesh_are_worked_on_in_bounded_pieces_with_the_same_answer(monkeypatch):
    mesh = trimesh.creation.icosphere(subdivisions=2)
    shape = Triangles(np.asarray(mesh.vertices), np.asarray(mesh.faces))
    origins, directions = rays(2, 600)
    whole = shape.entries(origins, directions, [0.0])
    monkeypatch.setattr(rayshapes, "_MESH_CHUNK", len(mesh.faces) * 7)  # 7 rays a piece
    np.testing.assert_array_equal(shape.entries(origins, directions, [0.0]), whole)


def test_a_geometry_rays_cannot_meet_is_refused_by_name():
    with pytest.raises(ValueError, match="kind 'torus'"):
        shape_of({"kind": "torus"}, AssetLibrary())
    assert isinstance(shape_of({"kind": "sphere", "radius": 1}, AssetLibrary()), Sphere)
