"""The observation vector's parts, and turns as axis × angle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from virtual_prosthetics.gym.observations import ObservationLayout, parts, turn_vector


def test_the_layout_names_every_part_in_order():
    layout = ObservationLayout(motors=6, digits=3)
    named = [name for name, _ in parts(6, 3)]
    assert named[:5] == ["time", "angles", "speeds", "efforts", "digitForces"]
    split = layout.split(np.arange(layout.size, dtype=np.float32))
    assert list(split) == named and layout.size == 1 + 3 * 6 + 3 + 3 + 4 + 3 + 3 + 3 + 4
    assert split["digitForces"].tolist() == [19, 20, 21]
    assert layout.space().shape == (layout.size,)


@pytest.mark.parametrize("angle", [0.3, -1.2, math.pi - 0.01])
def test_a_turn_is_its_axis_times_its_angle_the_short_way(angle):
    q = (0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2))
    assert turn_vector(q) == pytest.approx((0.0, angle, 0.0))
    assert turn_vector(tuple(-v for v in q)) == pytest.approx((0.0, angle, 0.0))  # the same turn
    assert turn_vector((0.0, 0.0, 0.0, 1.0)) == (0.0, 0.0, 0.0)
