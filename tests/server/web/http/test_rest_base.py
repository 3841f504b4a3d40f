"""What every REST route shares: a path naming what is not there is a structured 404 (code,
message, details; documented in the OpenAPI), a body past its limit is refused unread."""

import http.client
import json
import urllib.error

import pytest

from server.core.kit.limits import DEFAULT
from tests.conftest import WAIT_SECONDS


@pytest.mark.parametrize("path,code", [
    ("/api/scenes/no-such-scene", "unknown_scene"),
    ("/api/scenes/default/robots/nobody.1", "unknown_object"),
    ("/api/scenes/default/sensors/nobody.1", "unknown_object"),
    ("/api/scenes/no-such-scene/contacts", "unknown_scene"),
    ("/api/scenes/default/robots/nobody.1/urdf", "unknown_object"),
    ("/api/scenes/no-such-scene/robots/nobody.1/glb", "unknown_scene"),
])
def test_unknown_things_are_structured_404s(server, path, code):
    with pytest.raises(urllib.error.HTTPError) as caught:
        server.get(path)
    assert caught.value.code == 404
    assert json.loads(caught.value.read())["code"] == code


def test_a_refusal_names_what_was_missing_and_is_documented(server):
    with pytest.raises(urllib.error.HTTPError) as caught:
        server.get("/api/scenes/no-such-scene/robots/nobody.1")
    body = json.loads(caught.value.read())
    assert body["code"] == "unknown_scene" and "no-such-scene" in body["message"]
    assert body["details"] == {"scene": "no-such-scene"}
    documented = server.get("/openapi.json")
    refusal = documented["paths"]["/api/scenes/{scene}/robots/{robot_id}"]["get"]["responses"]["404"]
    schema = refusal["content"]["application/json"]["schema"]["$ref"].rsplit("/", 1)[-1]
    assert set(documented["components"]["schemas"][schema]["properties"]) == \
        {"code", "message", "details"}


def test_a_body_past_its_limit_is_refused_before_the_rest_is_sent(server):
    """(A client announcing 1 GB gets its refusal after the first bytes past the limit, not
    after uploading the gigabyte.)"""
    limit = DEFAULT.document_bytes  # (the shared server's)
    connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=WAIT_SECONDS)
    try:
        connection.putrequest("POST", "/api/scenes/default/import")
        connection.putheader("Content-Type", "application/json")
        connection.putheader("Content-Length", str(1 << 30))
        connection.endheaders()
        sent = 0
        while sent <= limit:
            connection.send(b" " * (1 << 16))
            sent += 1 << 16
        answer = connection.getresponse()
        error = json.loads(answer.read())
    finally:
        connection.close()
    assert answer.status == 413 and error["code"] == "too_large"
    assert error["details"]["limit"] == "documentBytes" and error["details"]["value"] == limit
