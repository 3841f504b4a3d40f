"""What Foxglove draws from a recording: the entities and transforms fit Foxglove's own
JSON Schemas (npm's @foxglove/schemas) and put every part where the scene has it."""

import base64
import io
import json
import subprocess

import fastjsonschema
import numpy as np
import pytest
import trimesh

from server.core.model.hands import RoundHand
from server.core.model.parts import Ball
from server.core.recording import foxglove
from tests.conftest import ROOT

SCRIPT = ("import {SceneUpdate, FrameTransforms} from '@foxglove/schemas/jsonschema.js';"
          "console.log(JSON.stringify({SceneUpdate, FrameTransforms}))")


@pytest.fixture(scope="module")
def official():
    """Foxglove's JSON Schemas, from its npm package (the client's dev dependency)."""
    out = subprocess.run(["node", "--input-type=module", "-e", SCRIPT], cwd=ROOT / "clients" / "js",
                         capture_output=True, text=True, check=True, timeout=60)
    return {name: fastjsonschema.compile(schema) for name, schema in json.loads(out.stdout).items()}


def test_the_scene_update_has_every_part_with_its_look_and_fits_foxglove(scene, official):
    hand = RoundHand(scene, "h", True)
    Ball(scene, "b", 0.5, "orange").set_position((3, 1, 0))
    scene.tick(1 / 60)
    update = foxglove.scene_update(scene, 1_700_000_000_123_456_789, scene.assets)
    official["SceneUpdate"](json.loads(json.dumps(update)))
    parts = {p.id for p in hand.get_parts() if p.physical} | {"b"}
    assert {e["id"] for e in update["entities"]} == parts
    assert all(e["frame_id"] == e["id"] for e in update["entities"])
    ball = next(e for e in update["entities"] if e["id"] == "b")["models"][0]
    mesh = trimesh.load(io.BytesIO(base64.b64decode(ball["data"])), file_type="glb")
    assert mesh.bounds == pytest.approx(np.array([[-0.5] * 3, [0.5] * 3]), abs=1e-3)
    assert update["entities"][0]["timestamp"] == {"sec": 1_700_000_000, "nsec": 123_456_789}


def test_transforms_place_each_moved_part_in_the_world_and_fit_foxglove(scene, official):
    hand = RoundHand(scene, "h", True)
    hand.set_position((1, 2, 3))
    scene.tick(1 / 60)
    hand.flex_finger(2, 0.8)
    messages = scene.tick(1 / 60)
    moved = foxglove.moved(scene, messages, {})
    assert moved and {n.id for n in moved} <= {p.id for p in hand.get_parts()}
    sent = foxglove.transforms(moved, 5)
    official["FrameTransforms"](sent)
    for transform, node in zip(sent["transforms"], moved):
        assert transform["parent_frame_id"] == "world" and transform["child_frame_id"] == node.id
        where = [transform["translation"][k] for k in "xyz"]
        assert where == pytest.approx(list(node.world_pose()[0]), abs=1e-6)
