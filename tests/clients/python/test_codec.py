"""Infinity and NaN both ways, and objects as references: the Python client's one codec."""

from __future__ import annotations

import math

from virtual_prosthetics.codec import encode_arg, from_wire, wire_number


class Thing:
    _scene = None
    id = "c3.4"


def test_non_finite_numbers_travel_as_strings_and_come_back():
    for value, wire in ((math.inf, "Infinity"), (-math.inf, "-Infinity")):
        assert wire_number(value) == wire and from_wire(wire) == value
    assert wire_number(math.nan) == "NaN" and math.isnan(from_wire("NaN"))
    assert wire_number(1.5) == 1.5 and from_wire("crimson") == "crimson"


def test_arguments_encode_objects_as_references_inside_lists():
    assert encode_arg([Thing(), math.inf, 2]) == [{"ref": "c3.4"}, "Infinity", 2]
