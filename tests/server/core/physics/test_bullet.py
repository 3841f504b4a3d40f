"""PyBullet imported without its banner (the server's output is its log), and the
collision shape of every part geometry: each makes a shape Bullet takes, of the part's
size; a sphere of radius 0 a hair's, not a refusal that ends the process."""

import subprocess
import sys

import pybullet as raw
import pytest

from server.core.physics.bullet import pybullet, shape_arguments
from tests.conftest import ROOT

GEOMETRIES = [
    ({"kind": "sphere", "radius": 0.5}, (-0.5, 0.5)),
    ({"kind": "sphere", "radius": 0.0}, (-0.01, 0.01)),
    ({"kind": "box", "size": [0.2, 0.4, 1.0]}, (-0.5, 0.5)),
    ({"kind": "convex", "points": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]}, (0.0, 1.0)),
    ({"kind": "cylinder", "radiusTop": 0.3, "radiusBottom": 0.3, "height": 2.0, "segments": 12},
     (-1.0, 1.0)),
]


def test_importing_it_prints_nothing():
    """(PyBullet's own import prints when it was built, on the server's output.)"""
    ran = subprocess.run([sys.executable, "-c", "import server.core.physics.bullet"], cwd=ROOT,
                         capture_output=True, text=True, check=True)
    assert (ran.stdout, ran.stderr) == ("", "")


@pytest.mark.parametrize("geometry, extent", GEOMETRIES)
def test_every_part_geometry_is_a_collision_shape_of_its_size(geometry, extent):
    client = raw.connect(raw.DIRECT)
    try:
        shape = raw.createCollisionShape(physicsClientId=client, **shape_arguments(geometry))
        body = raw.createMultiBody(0, shape, physicsClientId=client)
        low, high = raw.getAABB(body, physicsClientId=client)
        margin = 0.05  # Bullet's AABBs carry its collision margin
        assert min(low) == pytest.approx(extent[0], abs=margin)
        assert max(high) == pytest.approx(extent[1], abs=margin)
    finally:
        raw.disconnect(client)
    assert pybullet is raw  # the module itself, imported quietly


def test_an_unknown_geometry_is_a_clear_error():
    with pytest.raises(ValueError, match="plane"):
        shape_arguments({"kind": "plane"})
