"""Every generated file is what its generator makes now (``make generate`` writes them all).

Text is compared exactly. A mesh is compared as geometry, within a micrometre of a scene
unit: its vertices come from trigonometry, whose last bits may differ between machines."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import trimesh

import generate
from tests.conftest import ROOT


def _glb(data: bytes) -> trimesh.Trimesh:
    return trimesh.load(io.BytesIO(data), file_type="glb", force="mesh", process=False)


def _drifted(path: Path, made: str | bytes) -> bool:
    if isinstance(made, str):
        return path.read_text() != made
    ours, stored = _glb(made), _glb(path.read_bytes())
    return not (np.allclose(ours.vertices, stored.vertices, atol=1e-6)
                and np.array_equal(ours.faces, stored.faces)
                and np.array_equal(ours.visual.vertex_colors, stored.visual.vertex_colors))


def test_every_generated_file_is_what_its_generator_makes():
    written = [generator.outputs() for generator in generate.GENERATORS]
    outputs = {path: made for one in written for path, made in one.items()}
    assert len(outputs) == sum(map(len, written))  # no file written by two generators
    assert all(path.is_relative_to(ROOT) for path in outputs)
    drifted = [str(path.relative_to(ROOT)) for path, made in outputs.items() if _drifted(path, made)]
    assert drifted == [], f"run: make generate ({', '.join(drifted)} drifted)"


def test_a_drifted_file_is_found(tmp_path):
    text, mesh = tmp_path / "a.json", tmp_path / "m.glb"
    text.write_text("{}\n")
    mesh.write_bytes(trimesh.creation.box().export(file_type="glb"))
    assert not _drifted(text, "{}\n") and _drifted(text, "{ }\n")
    assert not _drifted(mesh, mesh.read_bytes())
    assert _drifted(mesh, trimesh.creation.box((1, 1, 1.001)).export(file_type="glb"))
