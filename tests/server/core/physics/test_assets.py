"""Mesh files by safe names: 1.0's spellings found, anything pointing elsewhere refused,
uploads kept by the hash of their bytes."""

from __future__ import annotations

import hashlib
import os

import pytest
import trimesh

from server.core.physics.assets import AssetLibrary, plain_name
from server.core.kit.limits import DEFAULT
from server.core.kit.errors import BadAsset, Forbidden, UnknownAsset


@pytest.mark.parametrize("spelling", ["round-palm.glb", "../assets/gltf/round-palm.glb",
                                      "./assets/gltf/round-palm.glb", "assets/gltf/round-palm.glb",
                                      "/assets/gltf/round-palm.glb"])
def test_the_spellings_of_1_0_pages_find_a_bundled_file(spelling):
    path, url = AssetLibrary().locate(spelling)
    assert path.name == "round-palm.glb" and url == "/assets/gltf/round-palm.glb"


@pytest.mark.parametrize("name", ["../round-palm.glb", "../../etc/passwd", "/etc/passwd",
                                  "assets/gltf/../../server/cli.py", "round-palm.glb/..",
                                  "https://example.com/a.glb", "%2e%2e%2fa.glb", "a\\b.glb",
                                  "round-palm.glb\n", "round-palm.obj", "", ".glb", "a..glb"])
def test_names_that_point_elsewhere_are_forbidden(name):
    with pytest.raises(Forbidden):
        plain_name(name)


def test_a_missing_file_names_the_bundled_ones():
    with pytest.raises(UnknownAsset) as caught:
        AssetLibrary().mesh("no-such.glb")
    assert "round-palm.glb" in caught.value.message and "POST /api/assets" in caught.value.message


def test_an_upload_is_kept_by_its_hash_and_then_found(tmp_path):
    library = AssetLibrary(uploads=tmp_path)
    data = trimesh.creation.box().export(file_type="glb")
    stored = library.store(data, DEFAULT)
    assert stored["name"] == hashlib.sha256(data).hexdigest()[:32] + ".glb"
    assert library.store(data, DEFAULT) == stored and library.uploaded_names() == [stored["name"]]
    mesh = library.mesh(stored["name"])
    assert mesh.url == "/api/assets/" + stored["name"] and len(mesh.triangles) == 12
    assert library.mesh("/api/assets/" + stored["name"]) is mesh  # read once


def test_collecting_removes_only_old_uploads_nothing_uses(tmp_path):
    library = AssetLibrary(uploads=tmp_path)
    used, unused, recent = (library.store(trimesh.creation.icosphere(1, r).export(file_type="glb"),
                                          DEFAULT)["name"] for r in (0.1, 0.2, 0.3))
    for name in (used, unused):
        os.utime(tmp_path / name, (1000.0, 1000.0))  # uploaded long ago
    assert library.collect({used}, before=2000.0) == [unused]
    assert sorted(library.uploaded_names()) == sorted([used, recent])


def test_a_file_with_coordinates_out_of_bounds_is_refused(tmp_path):
    huge = trimesh.creation.box(extents=(5000, 1, 1)).export(file_type="glb")
    with pytest.raises(BadAsset):
        AssetLibrary(uploads=tmp_path).store(huge, DEFAULT)
    assert list(tmp_path.iterdir()) == []


def test_a_scene_process_parses_a_mesh_file_once(tmp_path, monkeypatch):
    library = AssetLibrary(uploads=tmp_path)
    data = trimesh.creation.icosphere(2, 0.5).export(file_type="glb")
    stored = library.store(data, DEFAULT)
    loads = []
    real = trimesh.load
    monkeypatch.setattr(trimesh, "load", lambda *args, **kwargs: loads.append(1) or real(*args, **kwargs))
    library.mesh(stored["name"])  # a process's first use: checked and read in one parse
    library.mesh(stored["name"])
    assert len(loads) == 1
