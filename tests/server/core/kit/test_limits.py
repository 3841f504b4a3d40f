"""Limits: one table, sent in hello, changed from the command line in either spelling."""

import pytest

from server.core.kit.limits import DEFAULT


def test_wire_names_are_camel_case_integers():
    wire = DEFAULT.wire()
    assert wire["sceneObjects"] == DEFAULT.scene_objects and wire["messageBytes"] == 1 << 20
    assert all(isinstance(v, int) and v > 0 for v in wire.values())


def test_assignments_change_copies():
    limits = DEFAULT.with_values(["sceneBodies=10", "bytes_per_second=5"])
    assert (limits.scene_bodies, limits.bytes_per_second) == (10, 5)
    assert DEFAULT.scene_bodies == 2_000
    for bad in ("nothing=1", "sceneBodies=0", "sceneBodies=x", "sceneBodies"):
        with pytest.raises(ValueError, match="expected NAME=N"):
            DEFAULT.with_values([bad])
