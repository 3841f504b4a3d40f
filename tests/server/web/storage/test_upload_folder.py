"""The upload folder: uploads kept by the hash of their bytes (once, whole), old unused
ones collected, bad ones refused before anything is written."""

from __future__ import annotations

import hashlib
import os

import pytest
import trimesh

from server.core.kit.errors import BadAsset, Forbidden
from server.core.kit.limits import DEFAULT
from server.core.physics.assets import AssetLibrary
from server.web.storage.upload_folder import UploadFolder


def test_an_upload_is_kept_by_its_hash_and_then_found(tmp_path):
    library = AssetLibrary(uploads=tmp_path)
    uploads = UploadFolder(library)
    data = trimesh.creation.box().export(file_type="glb")
    stored = uploads.store(data, DEFAULT)
    assert stored["name"] == hashlib.sha256(data).hexdigest()[:32] + ".glb"
    assert uploads.store(data, DEFAULT) == stored and library.uploaded_names() == [stored["name"]]
    mesh = library.mesh(stored["name"])
    assert mesh.url == "/api/assets/" + stored["name"] and len(mesh.triangles) == 12
    assert library.mesh("/api/assets/" + stored["name"]) is mesh  # read once


def test_collecting_removes_only_old_uploads_nothing_uses(tmp_path):
    library = AssetLibrary(uploads=tmp_path)
    uploads = UploadFolder(library)
    used, unused, recent = (uploads.store(trimesh.creation.icosphere(1, r).export(file_type="glb"),
                                          DEFAULT)["name"] for r in (0.1, 0.2, 0.3))
    for name in (used, unused):
        os.utime(tmp_path / name, (1000.0, 1000.0))  # uploaded long ago
    assert uploads.collect({used}, before=2000.0) == [unused]
    assert sorted(library.uploaded_names()) == sorted([used, recent])


def test_a_file_with_coordinates_out_of_bounds_is_refused(tmp_path):
    huge = trimesh.creation.box(extents=(5000, 1, 1)).export(file_type="glb")
    with pytest.raises(BadAsset):
        UploadFolder(AssetLibrary(uploads=tmp_path)).store(huge, DEFAULT)
    assert list(tmp_path.iterdir()) == []


def test_a_server_without_an_upload_folder_keeps_nothing():
    with pytest.raises(Forbidden):
        UploadFolder(AssetLibrary()).store(trimesh.creation.box().export(file_type="glb"), DEFAULT)


def test_a_file_is_never_seen_half_written(tmp_path):
    """What the folder lists is whole: a file is written aside, then renamed."""
    uploads = UploadFolder(AssetLibrary(uploads=tmp_path))
    stored = uploads.store(trimesh.creation.icosphere(3).export(file_type="glb"), DEFAULT)
    assert [p.name for p in tmp_path.iterdir()] == [stored["name"]]
    assert (tmp_path / stored["name"]).stat().st_size == stored["bytes"]
