"""What Foxglove's 3D panel draws from a recording: the scene's parts as entities and where
they are (its ``foxglove.SceneUpdate`` and ``foxglove.FrameTransforms``, in JSON).

Each physical part is one entity in a frame of its own (named by the part's id) carrying
its look as an embedded GLB model (:mod:`server.core.physics.glb_file`); the transforms
place each frame in ``world`` (+Y up, metres, as the scene has it), for the parts that moved
in a tick. The JSON Schemas below describe the fields written here, a subset of Foxglove's
own (tests/server/core/recording/test_foxglove.py checks the messages against those);
Foxglove knows the types by their names.
"""

from __future__ import annotations

import base64
from typing import Any, Iterable, Mapping, Sequence

import numpy as np

from ..model.node import Node
from ..physics.assets import AssetLibrary
from ..physics.glb_file import DrawnPart, glb_bytes
from ..scene.scene import Scene

WORLD = "world"
UNUSED = ("arrows", "cubes", "spheres", "cylinders", "lines", "triangles", "texts")  # always empty here
_TIME = {"type": "object", "properties": {"sec": {"type": "integer"}, "nsec": {"type": "integer"}}}
_XYZ = {"type": "object", "properties": {k: {"type": "number"} for k in "xyz"}}
_XYZW = {"type": "object", "properties": {k: {"type": "number"} for k in "xyzw"}}
TRANSFORMS_SCHEMA = {"title": "foxglove.FrameTransforms", "type": "object", "properties": {
    "transforms": {"type": "array", "items": {"type": "object", "properties": {
        "timestamp": _TIME, "parent_frame_id": {"type": "string"}, "child_frame_id": {"type": "string"},
        "translation": _XYZ, "rotation": _XYZW}}}}}
_MODEL = {"type": "object", "properties": {
    "pose": {"type": "object", "properties": {"position": _XYZ, "orientation": _XYZW}},
    "scale": _XYZ, "color": {"type": "object", "properties": {k: {"type": "number"} for k in "rgba"}},
    "override_color": {"type": "boolean"}, "url": {"type": "string"},
    "media_type": {"type": "string"}, "data": {"type": "string", "contentEncoding": "base64"}}}
SCENE_SCHEMA = {"title": "foxglove.SceneUpdate", "type": "object", "properties": {
    "deletions": {"type": "array", "items": {"type": "object", "properties": {
        "timestamp": _TIME, "type": {"type": "integer"}, "id": {"type": "string"}}}},
    "entities": {"type": "array", "items": {"type": "object", "properties": {
        "timestamp": _TIME, "frame_id": {"type": "string"}, "id": {"type": "string"},
        "lifetime": _TIME, "frame_locked": {"type": "boolean"}, "metadata": {"type": "array"},
        **{kind: {"type": "array"} for kind in UNUSED}, "models": {"type": "array", "items": _MODEL}}}}}}
DELETE_ALL = 1  # foxglove.SceneEntityDeletion type: every entity before the timestamp


def drawn(scene: Scene) -> list[Node]:
    """The physical parts of the scene (those with a body), parents first."""
    return [node for root in scene.roots() for node in drawn_below(root)]


def drawn_below(top: Node) -> list[Node]:
    """The physical parts of ``top``'s tree from ``top`` down."""
    return [node for node in top.walk()
            if getattr(node, "physical", False) and node.in_scene() and node.geometry() is not None]


def scene_update(scene: Scene, stamp_ns: int, assets: AssetLibrary) -> dict[str, Any]:
    """Every entity anew (what was drawn before is deleted first): a seek that finds only
    the last such message still has the whole scene."""
    stamp = _stamp(stamp_ns)
    entities = [{"timestamp": stamp, "frame_id": node.id, "id": node.id,
                 "lifetime": {"sec": 0, "nsec": 0}, "frame_locked": True, "metadata": [],
                 **{kind: [] for kind in UNUSED}, "models": [_model(node, assets)]}
                for node in drawn(scene)]
    return {"deletions": [{"timestamp": stamp, "type": DELETE_ALL, "id": ""}], "entities": entities}


def _model(node: Node, assets: AssetLibrary) -> dict[str, Any]:
    scale = node.world_scale()
    look = glb_bytes([DrawnPart(node.id, node.geometry(), ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)),  # type: ignore[arg-type]
                                getattr(node, "recolors", ()))], assets)
    return {"pose": {"position": {"x": 0, "y": 0, "z": 0}, "orientation": {"x": 0, "y": 0, "z": 0, "w": 1}},
            "scale": dict(zip("xyz", scale)), "color": {"r": 1, "g": 1, "b": 1, "a": 1},
            "override_color": False, "url": "", "media_type": "model/gltf-binary",
            "data": base64.b64encode(look).decode()}


def transforms(nodes: Sequence[Node], stamp_ns: int) -> dict[str, Any]:
    """Where each of ``nodes`` is in the world (to a micrometre and a 10⁻⁷ turn: what
    compresses, at a tenth of what Foxglove can show)."""
    stamp = _stamp(stamp_ns)
    poses = [node.world_pose() for node in nodes]
    positions = np.round(np.array([p for p, _ in poses], float).reshape(-1, 3), 6).tolist()
    rotations = np.round(np.array([q for _, q in poses], float).reshape(-1, 4), 7).tolist()
    return {"transforms": [
        {"timestamp": stamp, "parent_frame_id": WORLD, "child_frame_id": node.id,
         "translation": dict(zip("xyz", position)), "rotation": dict(zip("xyzw", rotation))}
        for node, position, rotation in zip(nodes, positions, rotations)]}


def moved(scene: Scene, messages: Iterable[Mapping[str, Any]],
          below: dict[str, list[Node]]) -> list[Node]:
    """The physical parts a tick's messages moved: below every node with a new pose or
    robot or motor with new angles (``below`` keeps each such node's parts: the caller
    empties it when parts come or go)."""
    tops = {key for message in messages if message.get("op") == "frame"
            for field in ("poses", "angles") for key in message.get(field) or {}}
    seen: dict[str, Node] = {}
    for key in tops:
        top = scene.nodes.get(key)
        if top is not None:
            if key not in below:
                below[key] = drawn_below(top)
            seen.update((node.id, node) for node in below[key])
    return list(seen.values())


def _stamp(ns: int) -> dict[str, int]:
    return {"sec": ns // 1_000_000_000, "nsec": ns % 1_000_000_000}
