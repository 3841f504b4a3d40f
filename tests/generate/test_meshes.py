"""The bundled meshes, made by generate/meshes.py and committed (their drift: test_generated)."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from generate import meshes
from server.core.model.part_figures import MESH_BLUE, MESH_BOUNDS, MESH_WHITE


def committed(name: str) -> trimesh.Trimesh:
    return trimesh.load(meshes.GLTF_DIR / name, force="mesh", process=False)


@pytest.mark.parametrize("name", sorted(MESH_BOUNDS))
def test_each_mesh_has_1_0s_bounding_box_and_two_colours(name: str) -> None:
    mesh = committed(name)
    assert np.allclose(mesh.bounds.T, MESH_BOUNDS[name], atol=1e-6)
    colours = {tuple(c) for c in np.unique(mesh.visual.vertex_colors[:, :3], axis=0)}
    assert colours == {tuple(np.round(np.array(c) * 255).astype(int)) for c in (MESH_WHITE, MESH_BLUE)}


@pytest.mark.parametrize("name", sorted(MESH_BOUNDS))
def test_flat_faces_are_white_and_curved_ones_blue(name: str) -> None:
    mesh = committed(name)
    white = mesh.visual.vertex_colors[mesh.faces[:, 0], 0] == 255
    # a flat face lies in a plane with many others; curved faces turn from one to the next
    normals = np.round(mesh.face_normals, 4)
    _, inverse, counts = np.unique(normals, axis=0, return_inverse=True, return_counts=True)
    in_big_plane = counts[inverse.ravel()] >= 8
    share = mesh.area_faces[white].sum() / mesh.area
    assert 0.1 < share < 0.9  # both colours show
    assert in_big_plane[white].mean() > 0.95
    assert in_big_plane[~white].mean() < 0.2


def test_a_mesh_is_closed_so_rays_and_hulls_see_a_solid() -> None:
    for name in MESH_BOUNDS:
        merged = committed(name)
        merged.merge_vertices(merge_tex=True, merge_norm=True)
        assert merged.is_watertight, name
