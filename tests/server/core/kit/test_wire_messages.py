"""Every wire message of the schema has one typed definition here, and back."""

import json
from typing import get_args, get_type_hints

from server.core.kit import wire_messages
from tests.conftest import ROOT

SCHEMA = json.loads((ROOT / "protocol" / "schema" / "protocol.json").read_text())["$defs"]


def ops(kind: str) -> set[str]:
    return set(SCHEMA[kind]["properties"]["op"]["enum"])


def test_every_message_of_the_schema_has_a_definition_and_back():
    assert set(wire_messages.CLIENT_MESSAGES) == ops("clientMessage")
    assert set(wire_messages.SERVER_MESSAGES) == ops("serverMessage")


def test_each_definition_has_the_schemas_keys_required_as_the_schema_says():
    for op, message in {**wire_messages.CLIENT_MESSAGES, **wire_messages.SERVER_MESSAGES}.items():
        schema = SCHEMA[op]
        assert set(get_type_hints(message)) == set(schema["properties"]), op
        assert message.__required_keys__ == set(schema["required"]), op
        assert get_args(get_type_hints(message)["op"]) == (op,), op
