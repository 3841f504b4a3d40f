"""Envelopes of mesh parts: the hull, cut back at joints, thinned to a few dozen points."""

import numpy as np
import pytest
import trimesh
from scipy.spatial import ConvexHull

from server.core.physics.assets import AssetLibrary, MeshFile
from server.core.physics.envelopes import envelope, half_space, pyramid


def box_mesh(size=(1.0, 2.0, 1.0)) -> MeshFile:
    box = trimesh.creation.box(extents=size)
    return MeshFile("box", np.asarray(box.vertices, float), np.asarray(box.faces))


def test_without_cuts_a_box_is_its_eight_corners():
    points = envelope(box_mesh(), (0, 1, 0), mirror=False)
    assert sorted(points) == sorted((x, y, z) for x in (-0.5, 0.5) for y in (0, 2) for z in (-0.5, 0.5))


def test_a_half_space_keeps_what_lies_behind_it_by_the_gap():
    points = np.array(envelope(box_mesh(), (0, 0, 0), False, [half_space((0, 0.5, 0), (0, 1, 0), 0.1)]))
    assert points[:, 1].max() == pytest.approx(0.4) and points[:, 1].min() == pytest.approx(-1)


def test_a_pyramid_keeps_its_faces_at_45_degrees_from_the_gap_on():
    points = np.array(envelope(box_mesh(), (0, 1, 0), False, pyramid((0, 0, 0), (0, 1, 0), 0.05)))
    lateral = np.hypot(points[:, 0], points[:, 2])
    assert (points[:, 1] >= 0.05 + lateral * np.cos(np.pi / 8) - 1e-9).all()
    assert points[:, 1].min() == pytest.approx(0.05)  # the tip of the cut pyramid
    across = envelope(box_mesh(), (0, 1, 0), False, pyramid((0, 0, 0), (0, 1, 0), 0.05, [(1, 0, 0), (-1, 0, 0)]))
    assert min(p[1] for p in across if abs(p[0]) < 1e-9) == pytest.approx(0.05)
    assert max(abs(p[2]) for p in across if p[1] < 0.051) == pytest.approx(0.5)  # no slope in Z


def test_cuts_that_would_leave_nothing_leave_the_whole_hull():
    points = envelope(box_mesh(), (0, 0, 0), False, [half_space((0, -2, 0), (0, 1, 0), 0)])
    assert sorted(points) == sorted(envelope(box_mesh(), (0, 0, 0), False))


@pytest.fixture(scope="module")
def finger() -> MeshFile:
    return AssetLibrary().mesh("round-finger-8.glb")


def test_thinned_hull_stays_within_a_centimetre_of_the_whole_hull(finger):
    cuts = pyramid((0, 0, 0), (0, 1, 0), 0.01)
    whole = np.array(envelope(finger, (0, 0.4, 0), False, cuts, count=10_000))
    thin = np.array(envelope(finger, (0, 0.4, 0), False, cuts))
    assert 30 <= len(thin) <= 80 < len(whole)
    planes = ConvexHull(thin).equations
    assert (whole @ planes[:, :3].T + planes[:, 3]).max(axis=1).max() < 0.01


def test_a_symmetric_mesh_keeps_a_symmetric_envelope(finger):
    points = envelope(finger, (0, 0.4, 0), False, pyramid((0, 0, 0), (0, 1, 0), 0.01))
    points = np.array(points)
    for axis in (0, 2):
        mirrored = points * np.where(np.arange(3) == axis, -1, 1)
        assert max(np.linalg.norm(points - p, axis=1).min() for p in mirrored) < 1e-9


def test_a_mirrored_part_has_the_mirror_image_of_the_envelope():
    palm = AssetLibrary().mesh("round-palm.glb")
    cut = [half_space((0.3, 1.5, 0), (0.1, 1, 0), 0.02)]
    left = envelope(palm, (0, 0.7, 0), False, cut)
    right = envelope(palm, (0, 0.7, 0), True, [half_space((-0.3, 1.5, 0), (-0.1, 1, 0), 0.02)])
    assert sorted((-x, y, z) for x, y, z in right) == sorted(left)
