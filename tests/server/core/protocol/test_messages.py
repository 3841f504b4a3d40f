"""Decoding limits and schema checks of incoming messages."""

import json

import fastjsonschema
import pytest

from server.core.protocol import messages
from server.core.protocol.messages import check_client_message, validator
from server.core.kit.errors import BadJSON, BadMessage, LimitExceeded, TooLarge, UnknownOp


def test_decode_accepts_an_object_or_an_array():
    assert messages.decode('{"op": "ping"}') == [{"op": "ping"}]
    assert messages.decode('[{"op": "ping"}, {"op": "ping"}]') == [{"op": "ping"}] * 2


def test_oversize_text_is_refused_before_parsing():
    with pytest.raises(TooLarge):
        messages.decode(" " * (messages.DEFAULT.message_bytes + 1))


def test_too_many_messages_in_one_text():
    with pytest.raises(LimitExceeded):
        messages.decode("[" + ",".join(["{}"] * (messages.DEFAULT.messages_per_text + 1)) + "]")


@pytest.mark.parametrize("text", ["NaN", "[Infinity]", '{"a": -Infinity}', "{", ""])
def test_non_json_is_refused(text):
    with pytest.raises(BadJSON):
        messages.decode(text)


def test_deep_nesting_is_refused_not_crashed():
    with pytest.raises(BadJSON):
        messages.decode("[" * 100_000 + "]" * 100_000)


def test_schema_errors_name_the_field():
    with pytest.raises(BadMessage, match="args"):
        messages.check_client_message({"op": "call", "object": "a", "method": "m", "args": 5})
    with pytest.raises(UnknownOp):
        messages.check_client_message({"op": "frame"})


def test_a_bare_non_finite_number_cannot_pass_for_a_number():
    # a server bug: it goes out as null, which the schema refuses where a number belongs
    text = messages.encode({"op": "frame", "seq": 1, "time": float("inf")})
    with pytest.raises(fastjsonschema.JsonSchemaException):
        messages.check_server_message(json.loads(text))


def test_encode_writes_what_the_standard_library_writes():
    message = {"op": "frame", "seq": 7, "time": 0.1 + 0.2, "angles": {"c1.h": [1e-300, -0.0, 2 ** 60]},
               "sensors": {"c1.s": {"distance": "Infinity", "objects": ["é", "\u2028"]}},
               "big": 10 ** 30}
    assert messages.encode(message) == json.dumps(message, separators=(",", ":"))


def test_decode_reads_what_the_standard_library_reads():
    for text in ['{"op": "call", "args": [1e400, 0.1, -0.0, 9007199254740993]}',
                 '{"op": "x", "a": "\\ud800"}', '{"op": "x", "b": "\\u00e9\\n"}']:
        assert messages.decode(text) == [json.loads(text)]


def test_decode_reads_integers_beyond_64_bits_as_javascript_does():
    [message] = messages.decode('{"op": "x", "n": -123456789012345678901234567890}')
    assert message["n"] == -1.2345678901234568e+29 and type(message["n"]) is float


@pytest.mark.parametrize("message", [
    {"op": "call", "id": 1, "object": "c1.h", "method": "setAngles", "args": [0.5, -1, 2.0]},
    {"op": "call", "id": 1, "object": "c1.h", "method": "setAngles", "args": [0.5] * 10_001},
    {"op": "call", "id": 1, "object": "c1.h", "method": "setAngles", "args": [0.5, True]},
    {"op": "call", "id": -1, "object": "c1.h", "method": "setAngles", "args": [0.5]},
    {"op": "call", "object": "c1.h", "method": "x" * 65, "args": [1]},
    {"op": "call", "object": "c1.h", "method": "setAngles", "args": [1], "extra": 1},
    {"op": "call", "object": "c1.h", "method": "setAngles", "args": []},
    {"op": "call", "object": "c1.h", "method": "spreadFingers", "args": [0.2, False, None]},
    {"op": "call", "object": "c1.h", "method": "spreadFingers", "args": [0.2, True]},
    {"op": "call", "object": "c1.h", "method": "spreadFingers", "args": [0.2, True], "id": 2},
    {"op": "call", "object": "c1.h", "method": "spreadFingers", "args": [0.2, "x" * 201]},
    {"op": "call", "object": ["c1.h"], "method": "spreadFingers", "args": [0.2]},
    {"op": "call", "object": "c1 h", "method": "spreadFingers", "args": [0.2]},
    {"op": "call", "object": "c1.h", "method": {"x": 1}, "args": [0.2]},
    {"op": "call", "object": "c1.h", "method": 7, "args": [0.2]},
])
def test_calls_with_plain_numbers_are_judged_as_the_schema_judges_them(message):
    """Such calls skip the per-argument check (each number, boolean or null is a valid
    argument as it is), and a call without an id whose object and method passed before
    is not checked again: what passes and what fails must still be exactly what the
    schema says, the second time too."""
    try:
        validator("call")(message)
        expected = None
    except fastjsonschema.JsonSchemaValueException:
        expected = BadMessage
    for _ in range(2):
        if expected is None:
            assert check_client_message(message) is message
        else:
            with pytest.raises(expected):
                check_client_message(message)


def test_a_call_whose_object_and_method_passed_is_still_refused_for_anything_else():
    good = {"op": "call", "object": "c1.h", "method": "flexFingers", "args": [0.5]}
    assert check_client_message(good) is good
    for wrong in ({**good, "extra": 1}, {**good, "id": -1}, {**good, "op": "ping"},
                  {**good, "args": [[1, {"bad": "ref"}]]}):
        with pytest.raises((BadMessage, UnknownOp)):
            check_client_message(wrong)


def _batch_variants():
    call = {"op": "call", "object": "c1.h", "method": "flexFingers", "args": [0.5]}
    create = {"op": "create", "object": "c1.b", "type": "Box", "args": [{"ref": "c1.h"}, 1]}
    delete = {"op": "delete", "object": "c1.b"}
    good = [call, create, delete, {**call, "args": ["NaN", None]}]
    bad = [{**call, "id": 3}, {**call, "op": "ping"}, {**call, "extra": 1}, {**create, "type": 5},
           {**delete, "object": "no spaces allowed"}, {**call, "args": [True, {"ref": 1}]},
           {"op": "batch", "ops": [call]}, [call], "call", {**create, "args": [[1] * 3]}]
    yield {"op": "batch", "id": 1, "ops": good}
    yield {"op": "batch", "ops": [call] * 10_001}
    yield {"op": "batch", "ops": [call]}
    yield {"op": "batch", "id": 1, "ops": good, "extra": True}
    yield {"op": "batch", "id": -5, "ops": good}
    for position in (0, 1, 3):
        for wrong in bad:
            ops = list(good)
            ops.insert(position, wrong)
            yield {"op": "batch", "id": 2, "ops": ops}


@pytest.mark.parametrize("message", list(_batch_variants()))
def test_batches_are_judged_as_the_schema_judges_them_with_the_same_complaint(message):
    """A batch's operations are checked one by one through their own definitions (the
    compiled ``batchOp`` is slow): what passes, what fails and what the refusal says must
    be exactly what checking the whole batch against the schema gives."""
    try:
        validator("batch")(message)
        expected = None
    except fastjsonschema.JsonSchemaValueException as error:
        expected = messages._schema_refusal(error, "batch", "message").message
    if expected is None:
        assert check_client_message(message) is message
    else:
        with pytest.raises(BadMessage) as refused:
            check_client_message(message)
        assert refused.value.message == expected
