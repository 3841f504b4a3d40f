"""Protocol facts each side writes down for itself, held equal to the one source."""

from __future__ import annotations

import json
import re

from server.core.protocol.messages import CLIENT_OPS
from server.web.scenes.scene_hub import REPLACED
from tests.conftest import ROOT
from virtual_prosthetics import connection, protocol


def js_constant(path: str, pattern: str) -> str:
    return re.search(pattern, (ROOT / "clients" / "js" / path).read_text()).group(1)


def schema_ops(message: str) -> set[str]:
    schema = json.loads((ROOT / "protocol" / "schema" / "protocol.json").read_text())
    return set(schema["$defs"][message]["properties"]["op"]["enum"])


def test_the_server_takes_the_client_messages_of_the_schema():
    assert set(CLIENT_OPS) == schema_ops("clientMessage")


def test_every_side_knows_the_server_messages_of_the_schema():
    ops = schema_ops("serverMessage")
    assert set(protocol.SERVER_OPS) == ops
    assert set(json.loads(js_constant("wire_messages.js", r"SERVER_OPS = Object\.freeze\((\[.*?\])\)")
                          .replace("'", '"'))) == ops


def test_every_side_knows_the_close_code_of_a_replaced_connection():
    assert connection.REPLACED == REPLACED == int(js_constant("transport.js", r"REPLACED = (\d+)"))


def test_every_client_waits_as_long_before_connecting_again():
    first = int(js_constant("backoff.js", r"FIRST_PAUSE_MS = (\d+)"))
    longest = int(js_constant("backoff.js", r"LONGEST_PAUSE_MS = (\d+)"))
    assert (connection.RETRY_FIRST, connection.RETRY_MAX) == (first / 1000, longest / 1000)
