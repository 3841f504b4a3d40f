"""A glTF file judged from its layout alone, before a mesh library reads a byte of it.

A few hundred kilobytes of glTF can describe gigabytes: one mesh placed by a thousand
nodes is a thousand meshes once loaded, accessors may read the same bytes many times over,
a buffer may claim 2^40 bytes, and indices may point past the vertices. trimesh believes
what the file says, so everything it would build is counted here first, from the JSON and
the chunk and buffer lengths, and a file is refused before it costs anything:

- the container: a GLB's header, version and chunk lengths tile the file exactly, its
  first chunk is JSON; a glTF is JSON whose buffers are all embedded (``data:`` URIs);
- nothing it needs is missing: no required extension (Draco, quantization: not read here),
  no sparse accessor; buffers, views and accessors lie inside the bytes they name;
- what loading would expand to: each mesh's triangles and vertices times the times the
  scenes place it (nodes form a forest, no cycles), within ``assetTriangles``;
- every index lies below its primitive's vertex count.

Hand-written because the field's validators (Khronos' glTF-Validator) are JavaScript or
native programs, and no Python library counts the expansion before loading.
"""

from __future__ import annotations

import base64
import binascii
import json
import struct
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..kit.errors import BadAsset, LimitExceeded
from ..kit.limits import Limits

GLB_MAGIC, JSON_CHUNK, BIN_CHUNK = b"glTF", b"JSON", b"BIN\x00"
COMPONENT_BYTES = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}
INDEX_DTYPES = {5121: "<u1", 5123: "<u2", 5125: "<u4"}
TYPE_SIZES = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
TRIANGLES, STRIP, FAN = 4, 5, 6
ACCESSOR_SHARE = 4  # accessors may read at most this many times the file's bytes in all
# Items of each kind (accessors, nodes, ...) and node placements a file may have: trimesh
# spends ~0.3 ms of Python on each placement and ~60 µs on each accessor, so a few
# kilobytes of JSON could otherwise keep it busy for minutes. A detailed hand has hundreds.
MAX_ITEMS = 4096


@dataclass(frozen=True)
class GltfSummary:
    """What a checked file is and what loading it makes."""

    kind: str        # "glb" or "gltf"
    document: dict[str, Any]
    triangles: int   # every placement of every mesh, as a loader concatenates them
    vertices: int


@dataclass(frozen=True)
class _Accessor:
    count: int
    component: int
    size: int        # components per element
    view: int | None
    offset: int


def inspect(data: bytes, limits: Limits) -> GltfSummary:
    """Check a glTF file's layout and count what it expands to; :class:`BadAsset` for a
    broken or unsupported file, :class:`LimitExceeded` for one that expands too far."""
    kind, document, binary = _container(data)
    buffers = _buffers(document, binary)
    views = _views(document, buffers)
    accessors = _accessors(document, views, len(data))
    meshes = _meshes(document, accessors, views)
    placed = _placements(document, len(meshes))
    triangles = sum(t * max(1, placed[m]) for m, (t, _) in enumerate(meshes))
    vertices = sum(v * max(1, placed[m]) for m, (_, v) in enumerate(meshes))
    if triangles > limits.asset_triangles or vertices > 3 * limits.asset_triangles:
        raise LimitExceeded(
            f"the file's meshes, placed as its nodes place them, make {triangles} triangles "
            f"and {vertices} vertices; at most {limits.asset_triangles} triangles (and three "
            f"times as many vertices) are taken", limit="assetTriangles",
            value=limits.asset_triangles)
    if triangles == 0:
        raise BadAsset("the file holds no triangles")
    return GltfSummary(kind, document, triangles, vertices)


def _fail(message: str) -> BadAsset:
    return BadAsset(message[:300])


def _container(data: bytes) -> tuple[str, dict[str, Any], bytes | None]:
    """The kind, the JSON document and (GLB) the binary chunk."""
    if data[:4] != GLB_MAGIC:
        return "gltf", _json(data), None
    if len(data) < 20:
        raise _fail("the file is a GLB too short for its header")
    version, length = struct.unpack_from("<II", data, 4)
    if version != 2:
        raise _fail(f"the file is a GLB of version {version}; only glTF 2 is read")
    if length != len(data):
        raise _fail(f"the GLB header says {length} bytes; the file has {len(data)}")
    chunks: list[tuple[bytes, bytes]] = []
    at = 12
    while at < length:
        if length - at < 8:
            raise _fail(f"a chunk header at byte {at} is cut off")
        size, kind = struct.unpack_from("<I4s", data, at)
        if size > length - at - 8:
            raise _fail(f"the chunk at byte {at} says {size} bytes; {length - at - 8} are left")
        chunks.append((kind, data[at + 8:at + 8 + size]))
        at += 8 + size
    if not chunks or chunks[0][0] != JSON_CHUNK:
        raise _fail("the GLB's first chunk is not JSON")
    binary = chunks[1][1] if len(chunks) > 1 and chunks[1][0] == BIN_CHUNK else None
    return "glb", _json(chunks[0][1]), binary


def _json(text: bytes) -> dict[str, Any]:
    try:
        document = json.loads(text)
    except (ValueError, UnicodeDecodeError, RecursionError):
        raise _fail("the file is neither GLB nor glTF JSON") from None
    if not isinstance(document, dict) or not isinstance(document.get("asset"), dict):
        raise _fail("the file is not glTF: it has no 'asset' object")
    required = document.get("extensionsRequired")
    if required:
        names = ", ".join(str(n)[:40] for n in required) if isinstance(required, list) else "?"
        raise _fail(f"the file needs extensions this server does not read ({names}); "
                    f"export it without them")
    return document


def _items(document: dict[str, Any], group: str) -> list[dict[str, Any]]:
    items = document.get(group, [])
    if not isinstance(items, list) or not all(isinstance(i, dict) for i in items):
        raise _fail(f"'{group}' is not a list of objects")
    if len(items) > MAX_ITEMS:
        raise _fail(f"the file has {len(items)} {group}; at most {MAX_ITEMS} are read")
    return items


def _integer(item: dict[str, Any], key: str, where: str, default: int | None = None,
             low: int = 0) -> int:
    value = item.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        raise _fail(f"{where}: '{key}' must be a whole number of at least {low}")
    return value


def _index(item: dict[str, Any], key: str, where: str, count: int) -> int:
    value = _integer(item, key, where)
    if value >= count:
        raise _fail(f"{where}: '{key}' is {value}; there are {count}")
    return value


def _buffers(document: dict[str, Any], binary: bytes | None) -> list[bytes]:
    """Each buffer's bytes, at least as many as it says it has."""
    found = []
    for k, buffer in enumerate(_items(document, "buffers")):
        where = f"buffer {k}"
        claimed = _integer(buffer, "byteLength", where, low=1)
        uri = buffer.get("uri")
        if uri is None:
            if k != 0 or binary is None:
                raise _fail(f"{where} has no data: only a GLB's first buffer may leave out "
                            f"'uri'")
            data = binary
        elif isinstance(uri, str) and uri.startswith("data:") and ";base64," in uri[:200]:
            try:
                data = base64.b64decode(uri.partition(";base64,")[2], validate=True)
            except (binascii.Error, ValueError):
                raise _fail(f"{where}: its data: URI is not base64") from None
        else:
            raise _fail(f"the file refers to {str(uri)[:60]!r}; upload a GLB or a glTF with "
                        f"its buffers embedded (data: URIs)")
        if claimed > len(data):
            raise _fail(f"{where} says {claimed} bytes; it holds {len(data)}")
        found.append(data[:claimed])
    for k, image in enumerate(_items(document, "images")):
        uri = image.get("uri")
        if isinstance(uri, str) and not uri.startswith("data:"):
            raise _fail(f"the file refers to {uri[:60]!r}; upload a GLB or a glTF with its "
                        f"images embedded (data: URIs)")
    return found


def _views(document: dict[str, Any], buffers: list[bytes]) -> list[memoryview]:
    """Each buffer view's bytes (a view's stride is checked by the accessors using it)."""
    found = []
    for k, view in enumerate(_items(document, "bufferViews")):
        where = f"bufferView {k}"
        buffer = buffers[_index(view, "buffer", where, len(buffers))]
        offset = _integer(view, "byteOffset", where, default=0)
        length = _integer(view, "byteLength", where, low=1)
        if offset + length > len(buffer):
            raise _fail(f"{where} reads bytes {offset}-{offset + length} of a buffer of "
                        f"{len(buffer)}")
        found.append(memoryview(buffer)[offset:offset + length])
    return found


def _accessors(document: dict[str, Any], views: list[memoryview],
               file_bytes: int) -> list[_Accessor]:
    found, total = [], 0
    raw_views = _items(document, "bufferViews")
    for k, accessor in enumerate(_items(document, "accessors")):
        where = f"accessor {k}"
        if "sparse" in accessor:
            raise _fail(f"{where} is sparse; sparse accessors are not read here")
        component, kind = accessor.get("componentType"), accessor.get("type")
        size = TYPE_SIZES.get(kind) if isinstance(kind, str) else None
        if isinstance(component, bool) or not isinstance(component, int) or \
                component not in COMPONENT_BYTES or size is None:
            raise _fail(f"{where}: unknown componentType or type")
        count = _integer(accessor, "count", where, low=1)
        element = COMPONENT_BYTES[component] * size
        view = accessor.get("bufferView")
        offset = _integer(accessor, "byteOffset", where, default=0)
        if view is not None:
            view = _index(accessor, "bufferView", where, len(views))
            stride = _integer(raw_views[view], "byteStride", f"bufferView {view}",
                              default=element, low=element)
            if offset + stride * (count - 1) + element > len(views[view]):
                raise _fail(f"{where}: {count} elements of {element} bytes do not fit in "
                            f"bufferView {view} ({len(views[view])} bytes)")
        total += count * element
        found.append(_Accessor(count, component, size, view, offset))
    if total > ACCESSOR_SHARE * max(file_bytes, 1024):
        raise _fail(f"the file's accessors read {total} bytes from a file of {file_bytes}")
    return found


def _meshes(document: dict[str, Any], accessors: list[_Accessor],
            views: list[memoryview]) -> list[tuple[int, int]]:
    """(triangles, vertices) of each mesh, its indices checked."""
    found, primitive_count = [], 0
    for m, mesh in enumerate(_items(document, "meshes")):
        primitives = mesh.get("primitives")
        if not isinstance(primitives, list) or not all(isinstance(p, dict) for p in primitives):
            raise _fail(f"mesh {m}: 'primitives' is not a list of objects")
        primitive_count += len(primitives)
        if primitive_count > MAX_ITEMS:
            raise _fail(f"the file's meshes have more than {MAX_ITEMS} primitives")
        counts = [_primitive(p, f"mesh {m} primitive {k}", accessors, views)
                  for k, p in enumerate(primitives)]
        found.append((sum(t for t, _ in counts), sum(v for _, v in counts)))
    return found


def _primitive(primitive: dict[str, Any], where: str, accessors: list[_Accessor],
               views: list[memoryview]) -> tuple[int, int]:
    attributes = primitive.get("attributes")
    if not isinstance(attributes, dict) or "POSITION" not in attributes:
        raise _fail(f"{where} has no POSITION attribute")
    position = accessors[_index(attributes, "POSITION", where, len(accessors))]
    if position.component != 5126 or position.size != 3:
        raise _fail(f"{where}: POSITION must be VEC3 of floats")
    mode = _integer(primitive, "mode", where, default=TRIANGLES)
    if "indices" not in primitive:
        count = position.count
    else:
        indices = accessors[_index(primitive, "indices", where, len(accessors))]
        _check_indices(indices, position.count, where, views)
        count = indices.count
    if mode == TRIANGLES:
        if count % 3:
            raise _fail(f"{where}: {count} indices do not make whole triangles")
        return count // 3, position.count
    if mode in (STRIP, FAN):
        return max(0, count - 2), position.count
    return 0, position.count  # points and lines: no triangles


def _check_indices(indices: _Accessor, vertices: int, where: str,
                   views: list[memoryview]) -> None:
    if indices.size != 1 or indices.component not in INDEX_DTYPES:
        raise _fail(f"{where}: indices must be unsigned SCALARs")
    if indices.view is None:
        return  # all zero: a valid (if empty-looking) index
    values = np.frombuffer(views[indices.view], dtype=INDEX_DTYPES[indices.component],
                           count=indices.count, offset=indices.offset)
    highest = int(values.max())
    if highest >= vertices:
        raise _fail(f"{where}: index {highest} points past its {vertices} vertices")


def _placements(document: dict[str, Any], meshes: int) -> list[int]:
    """How many times the scenes place each mesh (nodes must form a forest)."""
    nodes = _items(document, "nodes")
    _check_forest(nodes, meshes)
    placed = [0] * meshes
    visits = 0
    for s, scene in enumerate(_items(document, "scenes")):
        roots = scene.get("nodes", [])
        if not isinstance(roots, list):
            raise _fail(f"scene {s}: 'nodes' is not a list")
        stack = [(root, 0) for root in roots]
        while stack:
            n, depth = stack.pop()
            if isinstance(n, bool) or not isinstance(n, int) or not 0 <= n < len(nodes):
                raise _fail(f"scene {s} names node {str(n)[:20]}, which does not exist")
            visits += 1
            if visits > MAX_ITEMS or depth > len(nodes):
                raise _fail(f"the file's scenes place more than {MAX_ITEMS} nodes (or its "
                            f"nodes form a cycle)")
            if "mesh" in nodes[n]:
                placed[nodes[n]["mesh"]] += 1
            stack.extend((child, depth + 1) for child in nodes[n].get("children", []))
    return placed


def _check_forest(nodes: list[Any], meshes: int) -> None:
    """Every child a node, no node the child of two (or of itself), every mesh one."""
    parents: dict[int, int] = {}
    for n, node in enumerate(nodes):
        children = node.get("children", [])
        if not isinstance(children, list):
            raise _fail(f"node {n}: 'children' is not a list")
        for child in children:
            if isinstance(child, bool) or not isinstance(child, int) or \
                    not 0 <= child < len(nodes):
                raise _fail(f"node {n}: child {str(child)[:20]} is not a node")
            if child in parents or child == n:
                raise _fail(f"node {child} has two parents; glTF nodes form a tree")
            parents[child] = n
        if "mesh" in node:
            _index(node, "mesh", f"node {n}", meshes)
