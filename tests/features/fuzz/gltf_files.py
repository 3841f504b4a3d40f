"""Structure-aware fuzzing of glTF uploads: valid files with their layout changed at random.

Each case starts from a small valid GLB or glTF and changes what a hostile file changes:
the GLB header and chunk lengths, buffer, view and accessor figures, the node graph
(placements, cycles, shared children), indices, extensions, modes and types. Every case
goes through the whole upload path (:meth:`AssetLibrary.store`, then reading it back as a
part would); it must be taken or refused with a VPError, nothing else.

Run as a program it fuzzes in a process of its own and prints a JSON summary with that
process's peak memory: ``python -m tests.features.fuzz.gltf_files --cases 10000``.
"""

from __future__ import annotations

import argparse
import base64
import copy
import json
import random
import struct
import sys
import tempfile
from pathlib import Path
from typing import Any, Callable

import trimesh

from server.core.physics.assets import AssetLibrary
from server.core.kit.limits import DEFAULT
from server.core.kit.errors import VPError
from server.web.storage.upload_folder import UploadFolder

ODD = [-1, 0, 1, 2, 3, 7, 255, 65535, 2 ** 31, 2 ** 32 - 1, 2 ** 40, 2 ** 63, 1e300, -0.0,
       float("nan"), "x", "", None, True, [], {}, [0], [0, 0], {"a": 1}, 5120, 5121, 5123,
       5125, 5126, "SCALAR", "VEC3", "MAT4"]
GROUPS = ("buffers", "bufferViews", "accessors", "meshes", "nodes", "scenes")


def glb_parts(data: bytes) -> tuple[dict[str, Any], bytes]:
    """The JSON document of a GLB and the bytes after its JSON chunk."""
    length = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + length]), data[20 + length:]


def pack_glb(document: Any, rest: bytes) -> bytes:
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<I4s", len(text), b"JSON") + text + rest
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def bases() -> list[tuple[str, bytes]]:
    """Valid starting points (JSON text, binary chunk): meshes with one node and several."""
    box = trimesh.creation.box().export(file_type="glb")
    two = trimesh.Scene([trimesh.creation.box(), trimesh.creation.icosphere(0, 0.5)])
    return [(json.dumps(document), rest) for document, rest in
            (glb_parts(box), glb_parts(two.export(file_type="glb")))]


def _set_field(rng: random.Random, document: dict[str, Any]) -> None:
    group = document.get(rng.choice(GROUPS))
    if not isinstance(group, list) or not group:
        return
    item = rng.choice(group)
    if not isinstance(item, dict):
        return
    keys = list(item) + ["byteStride", "sparse", "mode", "children", "byteOffset", "uri"]
    key = rng.choice(keys)
    if rng.random() < 0.2:
        item.pop(key, None)
    else:
        item[key] = copy.deepcopy(rng.choice(ODD))


def _place_many(rng: random.Random, document: dict[str, Any]) -> None:
    count = rng.choice([2, 50, 50, 50, 50, 4097])  # the last: past MAX_ITEMS
    start = len(document["nodes"])
    document["nodes"] += [{"mesh": 0} for _ in range(count)]
    document["scenes"][0]["nodes"] += list(range(start, start + count))


def _graph(rng: random.Random, document: dict[str, Any]) -> None:
    nodes = document["nodes"]
    nodes.append({"children": [0, 0] if rng.random() < 0.5 else [len(nodes)]})  # shared or self
    if rng.random() < 0.5:
        nodes[0]["children"] = [len(nodes) - 1]  # a cycle through node 0
    document["scenes"][0]["nodes"].append(len(nodes) - 1)


def _extension(rng: random.Random, document: dict[str, Any]) -> None:
    document["extensionsRequired"] = [rng.choice(["KHR_draco_mesh_compression",
                                                  "KHR_mesh_quantization", 7])]


def _accessor_reuse(rng: random.Random, document: dict[str, Any]) -> None:
    document["accessors"] += [dict(document["accessors"][0])
                              for _ in range(rng.choice([10, 10, 10, 10, 4097]))]


DOCUMENT_CHANGES: list[Callable[[random.Random, dict[str, Any]], None]] = [
    _set_field, _set_field, _set_field, _place_many, _graph, _extension, _accessor_reuse]


def _bytes_change(rng: random.Random, data: bytearray) -> bytes:
    """Header, chunk lengths, a cut, garbage, or raw bytes (indices) changed."""
    kind = rng.randrange(5)
    if kind == 0:
        struct.pack_into("<I", data, rng.choice([4, 8, 12, 16]), rng.choice(
            [0, 1, 2, 20, len(data) - 1, len(data) + 1, 2 ** 32 - 1]))
    elif kind == 1:
        return bytes(data[:rng.randrange(len(data))])
    elif kind == 2:
        return bytes(data) + bytes(rng.randrange(1, 64))
    else:
        for _ in range(rng.randrange(1, 8)):
            data[rng.randrange(20, len(data))] = rng.randrange(256)
    return bytes(data)


def case(rng: random.Random, starts: list[tuple[str, bytes]]) -> bytes:
    """One fuzzed file."""
    text, rest = rng.choice(starts)
    document = json.loads(text)
    for _ in range(rng.randrange(1, 4)):
        try:
            rng.choice(DOCUMENT_CHANGES)(rng, document)
        except (TypeError, KeyError, IndexError, AttributeError):
            pass  # an earlier change broke what this one changes: the file is odd enough
    if rng.random() < 0.15:  # the same as a glTF with its buffer embedded
        document.get("buffers", [{}])[0]["uri"] = \
            "data:application/octet-stream;base64," + base64.b64encode(rest[8:]).decode()
        return json.dumps(document).encode()
    data = pack_glb(document, rest)
    return _bytes_change(rng, bytearray(data)) if rng.random() < 0.4 else data


def fuzz(cases: int, seed: int = 0) -> dict[str, Any]:
    """Feed ``cases`` fuzzed files to the upload path; counts of each outcome, and the
    cases that failed otherwise than with a VPError (with their error)."""
    rng, starts = random.Random(seed), bases()
    library = AssetLibrary(uploads=Path(tempfile.mkdtemp(prefix="vp-gltf-fuzz-")))
    outcome: dict[str, Any] = {"cases": cases, "taken": 0, "refused": 0, "crashes": []}
    for number in range(cases):
        data = case(rng, starts)
        try:
            name = UploadFolder(library).store(data, DEFAULT)["name"]
            library.mesh(name)  # as a part reads it in a scene's process
            outcome["taken"] += 1
        except VPError:
            outcome["refused"] += 1
        except Exception as error:  # what the test reports
            outcome["crashes"].append([number, repr(error)[:200]])
    outcome["peakMegabytes"] = peak_megabytes()
    return outcome


def peak_megabytes(pid: int | str = "self") -> float:
    """The most memory a process has held so far (``VmHWM``: since its exec, where
    ``ru_maxrss`` would count the forking parent's size too)."""
    status = Path(f"/proc/{pid}/status").read_text()
    return int(status.split("VmHWM:")[1].split()[0]) / 1024


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--cases", type=int, default=10_000)
    parser.add_argument("--seed", type=int, default=0)
    options = parser.parse_args()
    json.dump(fuzz(options.cases, options.seed), sys.stdout)
