"""protocol/api.json: the API table as the clients read it, exported without drift."""

import json

from server.core.protocol import api, api_export


def test_protocol_api_json_is_the_exported_table():
    on_disk = api_export.API_PATH.read_text()
    assert on_disk == api_export.render(), "run: python -m server.core.protocol.api_export"


def test_api_json_has_every_type_with_its_methods_returns():
    table = json.loads(api_export.API_PATH.read_text())
    assert set(table["types"]) == set(api.TYPES)
    robot = table["types"]["Robot"]["methods"]
    assert robot["setPosition"]["returns"] == "self" and robot["attachChain"]["returns"] == "ref"
