"""Errors as clients see them: a refusal by a limit says how to change the limit."""

import pickle

from server.core.kit.limits import DEFAULT
from server.core.kit.errors import LimitExceeded, OutOfRange, TooLarge


def test_a_refusal_by_a_configurable_limit_names_its_value_and_the_flag_that_changes_it():
    for name in DEFAULT.wire():
        wire = LimitExceeded("too many", limit=name, value=7).to_wire(3, "call")
        assert wire["details"] == {"limit": name, "value": 7, "flag": f"--limit {name}=N"}
        assert wire["message"] == f"too many (limit {name}; vp-server --limit {name}=N changes it)"
    too_large = TooLarge("message of 9 bytes", limit="messageBytes", value=8)
    assert "--limit messageBytes=N" in too_large.message


def test_a_fixed_figure_names_no_flag_and_other_errors_are_unchanged():
    fixed = LimitExceeded("at most 16 recolors", limit="recolors", value=16)
    assert fixed.message == "at most 16 recolors" and "flag" not in fixed.details
    assert OutOfRange("bad", object="x").details == {"object": "x"}


def test_an_error_crossing_from_a_scene_process_says_it_once():
    error = LimitExceeded("full", limit="sceneObjects", value=5)
    again = pickle.loads(pickle.dumps(error))
    assert again.message == error.message and again.details == error.details
