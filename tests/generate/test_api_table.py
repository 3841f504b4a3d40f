"""protocol/api.json: the API table as the clients read it (its drift: test_generated)."""

import json

from generate import api_table
from server.core.protocol import api


def test_api_json_has_every_type_with_its_methods_returns():
    table = json.loads(api_table.API_PATH.read_text())
    assert set(table["types"]) == set(api.TYPES)
    robot = table["types"]["Robot"]["methods"]
    assert robot["setPosition"]["returns"] == "self" and robot["attachChain"]["returns"] == "ref"
