"""schemathesis against the live server's OpenAPI document: no 500s, documented answers.

Every operation of /openapi.json is called with generated paths, queries and bodies
(scene names, robot and sensor ids, ``other``, uploaded bytes), valid and not; each answer must be one the
document lists, with a body of the documented form, never a server error. A robot with
an unlimited motor and a sensor are in the scene meanwhile, so lookups that find
something are fuzzed too.
"""

import json
import threading

import pytest
import schemathesis
from schemathesis.checks import positive_data_acceptance
from hypothesis import HealthCheck, given, seed, settings
from websockets.sync.client import connect

from tests.server.web.ws_requests import request_all
from tests.conftest import WAIT_SECONDS

from . import CASES


@pytest.fixture(scope="module")
def api_schema(server):
    with connect(f"{server.ws}/ws?scene=default", max_size=None) as ws:
        me = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
        ws.recv(timeout=WAIT_SECONDS)
        request_all(ws, [
            {"op": "create", "object": f"{me}.h", "type": "EdgedHand"},
            {"op": "create", "object": f"{me}.s", "type": "Sensor"},
            {"op": "create", "object": f"{me}.r", "type": "Robot"},
            {"op": "create", "object": f"{me}.m", "type": "MotorZ",
             "args": ["-Infinity", "Infinity"]},
            {"op": "call", "object": f"{me}.r", "method": "attachChain",
             "args": [{"ref": f"{me}.m"}]},
        ])
        reader = threading.Thread(target=lambda: [None for _ in ws], daemon=True)
        reader.start()  # keeps reading, so the objects stay while the schema is fuzzed
        yield schemathesis.openapi.from_url(f"{server.http}/openapi.json")


@pytest.mark.fuzz
def test_every_rest_operation_answers_as_documented(api_schema):
    operations = [result.ok() for result in api_schema.get_all_operations()]
    assert len(operations) >= 8
    examples = -(-CASES // len(operations))  # CASES calls in all, at least
    for operation in operations:
        @seed(CASES)
        @settings(max_examples=examples, deadline=None, database=None,
                  suppress_health_check=list(HealthCheck))
        @given(case=operation.as_strategy())
        def call(case) -> None:
            case.call_and_validate(excluded_checks=excluded(case.operation))
        call()


def excluded(operation) -> list:
    """Checks that cannot apply: an upload's body may be any bytes by its schema, but only
    a glTF mesh is taken (tests/server/web/http/test_assets.py covers what is refused), and
    only a robot description a robot upload's (tests/server/web/http/test_robot_routes.py); an
    import's body any object, but only a scene document (tests/server/web/
    test_persistence.py)."""
    picky = operation.method.upper() == "POST" and operation.path in (
        "/api/assets", "/api/scenes/{scene}/import", "/api/robots", "/api/scenes/{scene}/robots")
    return [positive_data_acceptance] if picky else []
