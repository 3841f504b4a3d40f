"""Mesh files by safe names: 1.0's spellings found, anything pointing elsewhere refused,
a file parsed once per process."""

from __future__ import annotations

import pytest
import trimesh

from server.core.physics.assets import AssetLibrary, plain_name
from server.core.kit.limits import DEFAULT
from server.core.kit.errors import Forbidden, UnknownAsset
from server.web.storage.upload_folder import UploadFolder


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


def test_a_scene_process_parses_a_mesh_file_once(tmp_path, monkeypatch):
    library = AssetLibrary(uploads=tmp_path)
    data = trimesh.creation.icosphere(2, 0.5).export(file_type="glb")
    stored = UploadFolder(library).store(data, DEFAULT)
    loads = []
    real = trimesh.load
    monkeypatch.setattr(trimesh, "load", lambda *args, **kwargs: loads.append(1) or real(*args, **kwargs))
    library.mesh(stored["name"])  # a process's first use: checked and read in one parse
    library.mesh(stored["name"])
    assert len(loads) == 1
