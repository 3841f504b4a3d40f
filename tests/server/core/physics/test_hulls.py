"""Hulls of point sets without volume: thickened by a hair, never refused."""

import numpy as np
import pytest

from server.core.physics.hulls import HAIR, convex_hull


@pytest.mark.parametrize("points, flat_axes", [
    ([[0, 0, 0], [2, 0, 0], [0, 2, 0], [2, 2, 0]], 1),  # a square
    ([[0, 0, 0], [0, 3, 0]], 2),                          # a line
    ([[1, 1, 1]], 3),                                     # a point
])
def test_sets_without_volume_get_a_hair_of_depth(points, flat_axes):
    hull = convex_hull(points)
    corners = hull.points[hull.vertices]
    spans = np.ptp(corners, axis=0)
    assert sorted(spans)[:flat_axes] == pytest.approx([2 * HAIR * max(1.0, np.abs(np.array(points) - np.mean(points, axis=0)).max())] * flat_axes, rel=1e-3)
    assert np.abs(corners - np.mean(points, axis=0)).max() <= max(np.ptp(points, axis=0)) + 1e-8


def test_a_solid_set_is_left_as_it_is():
    cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    hull = convex_hull(cube)
    assert sorted(map(tuple, hull.points[hull.vertices])) == sorted(map(tuple, np.array(cube, float)))
    assert hull.volume == pytest.approx(1.0)
