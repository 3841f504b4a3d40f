"""A scene's physics settings: the options checked, their wire form, Bullet's units."""

import math

import pytest

from server.core.kit.errors import BadArguments, OutOfRange, WrongType
from server.core.physics.settings import DEFAULT_UNIT, BulletUnits, Physics


def test_options_left_out_take_their_defaults_and_the_wire_form_round_trips():
    physics = Physics.of("dynamic", {"gravity": 157, "substeps": 8})
    assert physics.dynamic and physics.gravity == 157.0 and physics.substeps == 8
    assert physics.solverIterations == Physics().solverIterations
    assert physics.step == pytest.approx(1 / 480)
    wire = physics.wire()
    assert Physics.of(wire.pop("mode"), wire) == physics
    assert not Physics.of("kinematic").dynamic


@pytest.mark.parametrize("mode, options, error, words", [
    ("floating", None, OutOfRange, "kinematic or dynamic"),
    ("dynamic", [9.81], WrongType, "object"),
    ("dynamic", {"gravitation": 9.81}, BadArguments, "gravitation"),
    ("dynamic", {"substeps": 2.5}, WrongType, "whole"),
    ("dynamic", {"substeps": 0}, OutOfRange, "[1, 20]"),
    ("dynamic", {"friction": True}, WrongType, "friction"),
    ("dynamic", {"gravity": math.inf}, WrongType, "gravity"),
    ("dynamic", {"density": 0.5}, OutOfRange, "density"),
    ("dynamic", {"solverTolerance": 2}, OutOfRange, "solverTolerance must be within [0.0, 1.0]"),
    ("dynamic", {"warmStart": 1.5}, OutOfRange, "warmStart must be within [0.0, 1.0]"),
])
def test_bad_options_are_refused_naming_what_was_wrong(mode, options, error, words):
    with pytest.raises(error) as refused:
        Physics.of(mode, options)
    assert words in refused.value.message


@pytest.mark.parametrize("unit", [DEFAULT_UNIT, 1.0, 0.001])
def test_a_density_in_kg_per_m3_is_the_same_number_in_bullets_units(unit):
    units = BulletUnits(unit)
    side = 2.0  # scene units: a cube of (2 unit)³ of water
    kilograms = 1000.0 * (side * unit) ** 3
    assert 1000.0 * side ** 3 * units.mass == pytest.approx(kilograms)
    # a newton is a kilogram's metre per second²: in Bullet, mass × scene units / s²
    assert units.force == pytest.approx(units.mass * unit)
    assert units.torque == pytest.approx(units.force * unit)
    assert units.acceleration(9.81) * unit == pytest.approx(9.81)
