"""Robots of random shape up to every limit (issue 44, G15): each answer ok or a
structured refusal, every tree whole in the engine, every scene ticking
(:mod:`tests.features.fuzz.trees`)."""

import pytest

from tests.conftest import run_program

from . import CASES

TREE_CASES = max(40, CASES // 25)  # (a case is a few hundred requests and PyBullet trees)


@pytest.mark.fuzz
def test_fuzzed_robot_shapes_are_built_whole_or_refused_naming_a_limit():
    summary = run_program("tests.features.fuzz.trees", "--cases", str(TREE_CASES))
    assert summary["broken"] == [] and summary["cases"] == TREE_CASES
    # the cases reach every limit a tree has, and most requests succeed
    assert set(summary["limits"]) == {"treeLinks", "treeDepth", "clientObjects", "sceneBodies"}, \
        summary["limits"]
    assert summary["answers"]["ok"] > 5 * summary["answers"]["limit_exceeded"], summary["answers"]
    assert summary["peakMegabytes"] < 400
