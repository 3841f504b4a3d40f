"""glTF files judged from their layout before anything is loaded: what they expand to,
what they point at, and 10 000 fuzzed files that are each taken or refused, never more."""

from __future__ import annotations

import base64
import json

import pytest
import trimesh

from server.core.physics.gltf_file import MAX_ITEMS, inspect
from server.core.kit.limits import DEFAULT
from server.core.kit.errors import BadAsset, LimitExceeded
from tests.conftest import run_program
from tests.features.fuzz import CASES
from tests.features.fuzz.gltf_files import glb_parts, pack_glb


@pytest.fixture(scope="module")
def sphere() -> tuple[dict, bytes]:
    """A 20 480-triangle sphere as a GLB's document and binary chunk."""
    return glb_parts(trimesh.creation.icosphere(5, 1.0).export(file_type="glb"))


def changed(start: tuple[dict, bytes], change) -> bytes:
    document, rest = json.loads(json.dumps(start[0])), start[1]
    change(document)
    return pack_glb(document, rest)


def test_a_valid_file_is_counted_as_loading_makes_it(sphere):
    summary = inspect(pack_glb(*sphere), DEFAULT)
    assert (summary.kind, summary.triangles, summary.vertices) == ("glb", 20480, 10242)


def test_one_mesh_placed_by_a_thousand_nodes_is_refused_before_it_is_loaded(sphere):
    def place(document):
        document["nodes"] = [{"mesh": 0} for _ in range(1000)]
        document["scenes"] = [{"nodes": list(range(1000))}]
    bomb = changed(sphere, place)
    assert len(bomb) < 500_000  # a few hundred kilobytes that would be 20 M triangles
    with pytest.raises(LimitExceeded) as refused:
        inspect(bomb, DEFAULT)
    assert "20480000 triangles" in refused.value.message
    assert refused.value.details == {"limit": "assetTriangles", "value": 200_000,
                                     "flag": "--limit assetTriangles=N"}


def test_placements_through_children_count_too(sphere):
    def nest(document):  # 10 groups of 10 nodes: 100 placements
        document["nodes"] = [{"mesh": 0} for _ in range(100)] + \
            [{"children": list(range(10 * k, 10 * k + 10))} for k in range(10)]
        document["scenes"] = [{"nodes": list(range(100, 110))}]
    with pytest.raises(LimitExceeded, match="2048000 triangles"):
        inspect(changed(sphere, nest), DEFAULT)


@pytest.mark.parametrize("change, words", [
    (lambda d: d["nodes"].append({"children": [0, 0]}), "two parents"),
    (lambda d: d["nodes"][0].update(children=[0]), "two parents"),
    (lambda d: (d["nodes"].append({"children": [0]}), d["nodes"][0].update(children=[1])),
     "cycle"),
    (lambda d: d["nodes"].extend({} for _ in range(MAX_ITEMS)), f"at most {MAX_ITEMS}"),
    (lambda d: d.update(extensionsRequired=["KHR_draco_mesh_compression"]),
     "extensions this server does not read (KHR_draco_mesh_compression)"),
    (lambda d: d["buffers"][0].update(byteLength=2 ** 40), f"says {2 ** 40} bytes"),
    (lambda d: d["bufferViews"][0].update(byteOffset=10 ** 9), "bufferView 0 reads bytes"),
    (lambda d: d["accessors"][0].update(count=10 ** 9), "do not fit in bufferView"),
    (lambda d: d["accessors"].extend([d["accessors"][1]] * 200), "accessors read"),
    (lambda d: d["accessors"][0].update(sparse={}), "sparse"),
    (lambda d: d["meshes"][0]["primitives"][0].update(indices=99), "'indices' is 99"),
    (lambda d: d["scenes"][0].update(nodes=[7]), "names node 7"),
])
def test_a_file_whose_layout_does_not_hold_is_refused(sphere, change, words):
    with pytest.raises(BadAsset) as refused:
        inspect(changed(sphere, change), DEFAULT)
    assert words in refused.value.message


def test_indices_past_the_vertices_are_refused(sphere):
    document, rest = sphere
    indices = document["accessors"][document["meshes"][0]["primitives"][0]["indices"]]
    view = document["bufferViews"][indices["bufferView"]]
    data = bytearray(rest)
    start = 8 + view.get("byteOffset", 0) + indices.get("byteOffset", 0)
    data[start:start + 4] = (10 ** 6).to_bytes(4, "little")  # the first index, far out
    with pytest.raises(BadAsset, match="index 1000000 points past its 10242 vertices"):
        inspect(pack_glb(document, bytes(data)), DEFAULT)


@pytest.mark.parametrize("length", [1, 20, 2 ** 32 - 1])
def test_a_glb_header_that_does_not_give_the_file_length_is_refused(sphere, length):
    data = bytearray(pack_glb(*sphere))
    data[8:12] = length.to_bytes(4, "little")
    with pytest.raises(BadAsset, match=f"header says {length} bytes"):
        inspect(bytes(data), DEFAULT)


def test_a_gltf_json_file_with_an_embedded_buffer_is_read_and_checked(sphere):
    document, rest = json.loads(json.dumps(sphere[0])), sphere[1]
    document["buffers"][0]["uri"] = "data:application/octet-stream;base64," + \
        base64.b64encode(rest[8:]).decode()
    assert inspect(json.dumps(document).encode(), DEFAULT).triangles == 20480
    document["buffers"][0]["byteLength"] += 1
    with pytest.raises(BadAsset, match="holds"):
        inspect(json.dumps(document).encode(), DEFAULT)


def test_deeply_nested_json_is_refused_as_not_gltf():
    with pytest.raises(BadAsset, match="neither GLB nor glTF"):
        inspect(b"[" * 100_000 + b"]" * 100_000, DEFAULT)


@pytest.mark.fuzz
def test_fuzzed_uploads_are_each_taken_or_refused_in_bounded_memory():
    outcome = run_program("tests.features.fuzz.gltf_files", "--cases", str(CASES))
    assert outcome["crashes"] == [] and outcome["cases"] == CASES
    assert outcome["taken"] > CASES / 10 and outcome["refused"] > CASES / 2  # both paths
    assert outcome["peakMegabytes"] < 400  # one 20 M-triangle load alone takes gigabytes
