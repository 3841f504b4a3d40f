"""Numbers JSON cannot carry travel as strings."""

import math

from server.core.kit.numbers import NON_FINITE, Finite, encode_numbers, wire_number


def test_non_finite_numbers_travel_as_their_names_and_come_back():
    assert [wire_number(x) for x in (1.5, math.inf, -math.inf)] == [1.5, "Infinity", "-Infinity"]
    assert wire_number(math.nan) == "NaN" and math.isnan(NON_FINITE["NaN"])
    assert [NON_FINITE[wire_number(x)] for x in (math.inf, -math.inf)] == [math.inf, -math.inf]


def test_every_number_inside_a_value_is_encoded_and_finite_ones_pass_as_they_are():
    value = {"min": -math.inf, "list": [1.0, (math.inf, 2)], "name": "Infinity"}
    assert encode_numbers(value) == {"min": "-Infinity", "list": [1.0, ["Infinity", 2]], "name": "Infinity"}
    known = Finite((1.0, 2.0))
    assert encode_numbers({"points": known})["points"] is known
