"""An imported link's look and envelope from its file's elements: one GLB painted as the
file says, one hull of what collides; an OBJ's material found inside the upload and
nowhere else; triangles past the limits refused by name."""

import io

import numpy as np
import pytest
import trimesh

from server.core.kit.errors import BadAsset, Forbidden, LimitExceeded
from server.core.kit.limits import DEFAULT
from server.core.physics.link_meshes import (DEFAULT_RGBA, ArchiveResolver, Element, MeshReader,
                                             _colours, box, drawn, envelope, sphere)
from server.core.physics.robot_archive import open_archive
from tests.hand_files import hand_urdf, zipped


def placed_at(x: float, y: float = 0.0, z: float = 0.0) -> np.ndarray:
    placement = np.eye(4)
    placement[:3, 3] = (x, y, z)
    return placement


def test_a_links_visuals_are_one_glb_placed_and_painted_as_the_file_says():
    red_box = Element(box((0.2, 0.2, 0.2)), placed_at(1.0), (1.0, 0.0, 0.0, 1.0))
    plain_ball = Element(sphere(0.1), placed_at(0.0))
    opened = trimesh.load(io.BytesIO(drawn([red_box, plain_ball], "palm", DEFAULT)),
                          file_type="glb", force="mesh")
    assert opened.bounds.ravel() == pytest.approx([-0.1, -0.1, -0.1, 1.1, 0.1, 0.1], abs=1e-3)
    colours = {tuple(c) for c in opened.visual.vertex_colors[:, :3]}
    default = tuple(round(c * 255) for c in DEFAULT_RGBA[:3])
    assert colours == {(255, 0, 0), default}
    assert drawn([], "palm", DEFAULT) is None  # a link with nothing to show


def test_a_link_drawn_with_too_many_triangles_is_refused_naming_the_limit():
    ball = Element(sphere(0.1), placed_at(0.0))  # 320 triangles
    with pytest.raises(LimitExceeded) as refused:
        drawn([ball], "palm", DEFAULT.with_values(["assetTriangles=300"]))
    assert refused.value.details["limit"] == "assetTriangles" and "palm" in refused.value.message


def test_the_envelope_is_the_hull_of_every_colliding_element_where_it_sits():
    points = np.asarray(envelope([Element(box((0.2, 0.2, 0.2)), placed_at(1.0)),
                                  Element(box((0.2, 0.2, 0.2)), placed_at(0.0, 0.5))]))
    assert points.min(axis=0) == pytest.approx([-0.1, -0.1, -0.1], abs=0.02)
    assert points.max(axis=0) == pytest.approx([1.1, 0.6, 0.1], abs=0.02)
    assert envelope([]) is None  # nothing collides


OBJ = b"mtllib tip.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl red\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"


def test_an_objs_material_is_read_from_the_upload_only():
    files = {"hand.urdf": hand_urdf(), "meshes/tip.obj": OBJ,
             "meshes/tip.mtl": b"newmtl red\nKd 1 0 0\n"}
    reader = MeshReader(open_archive(zipped(files), None, DEFAULT), DEFAULT)
    tip = reader.mesh("meshes/tip.obj", scale=2.0)
    assert len(tip.faces) == 4 and tip.bounds[1] == pytest.approx([2, 2, 2])
    # (found here: the material was never read, and the file's red was drawn grey)
    assert {tuple(c[:3]) for c in _colours(tip, None)} == {(255, 0, 0)}
    escaping = {**files, "meshes/tip.obj": OBJ.replace(b"tip.mtl", b"../../../etc/passwd")}
    archive = open_archive(zipped(escaping), None, DEFAULT)
    with pytest.raises(Forbidden):
        ArchiveResolver(archive, "meshes")["../../../etc/passwd"]
    outside = MeshReader(archive, DEFAULT).mesh("meshes/tip.obj")  # (trimesh goes without)
    assert {tuple(c[:3]) for c in _colours(outside, None)} == {
        tuple(round(c * 255) for c in DEFAULT_RGBA[:3])}


def test_a_robots_meshes_past_its_triangle_limit_are_refused():
    files = {"hand.urdf": hand_urdf(), "meshes/tip.obj": OBJ.replace(b"mtllib tip.mtl\n", b"")}
    archive = open_archive(zipped(files), None, DEFAULT)
    reader = MeshReader(archive, DEFAULT.with_values(["robotTriangles=6"]))
    reader.mesh("meshes/tip.obj")
    reader.mesh("meshes/tip.obj", scale=3.0)  # read once: counted once
    assert reader.budget.triangles == 4
    with pytest.raises(LimitExceeded) as refused:
        MeshReader(archive, DEFAULT.with_values(["robotTriangles=3"])).mesh("meshes/tip.obj")
    assert refused.value.details["limit"] == "robotTriangles"
    with pytest.raises(BadAsset, match="formats"):
        MeshReader(open_archive(zipped({**files, "meshes/tip.txt": b"x"}), None, DEFAULT),
                   DEFAULT).mesh("meshes/tip.txt")
