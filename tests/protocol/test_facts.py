"""Protocol facts each side writes down for itself, held equal to the one source."""

from __future__ import annotations

import json
import re

from server.web.scene_hub import REPLACED
from tests.conftest import ROOT
from virtual_prosthetics import connection, protocol


def js_constant(path: str, pattern: str) -> str:
    return re.search(pattern, (ROOT / "clients" / "js" / path).read_text()).group(1)


def test_every_side_knows_the_server_messages_of_the_schema():
    schema = json.loads((ROOT / "protocol" / "schema" / "protocol.json").read_text())
    ops = set(schema["$defs"]["serverMessage"]["properties"]["op"]["enum"])
    assert set(protocol.SERVER_OPS) == ops
    assert set(json.loads(js_constant("protocol.js", r"SERVER_OPS = Object\.freeze\((\[.*?\])\)")
                          .replace("'", '"'))) == ops


def test_every_side_knows_the_close_code_of_a_replaced_connection():
    assert connection.REPLACED == REPLACED == int(js_constant("transport.js", r"REPLACED = (\d+)"))
