"""CORS with a real server: pages of the origins the access policy allows (loopback ones by
rule, those given with --allow-origin) read the REST API and may send changes with the
token; pages of other sites get no CORS headers, so their browsers keep the answers."""

import http.client

from tests.conftest import WAIT_SECONDS

from .test_access import VIEW, locked  # noqa: F401 (the fixture: a server with tokens)


def answer_headers(server, method: str, path: str, headers: dict) -> tuple[int, dict]:
    connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=WAIT_SECONDS)
    try:
        connection.request(method, path, headers=headers)
        answer = connection.getresponse()
        answer.read()
        return answer.status, {k.lower(): v for k, v in answer.getheaders()}
    finally:
        connection.close()


def test_rest_answers_pages_of_allowed_origins_with_cors_headers(locked):
    """A page served from elsewhere reads scenes (and, with the token, may send changes);
    a page of another site gets no CORS headers, so its browser keeps the answer from it."""
    for origin in ("http://127.0.0.1:8080", "https://friend.example"):
        status, headers = answer_headers(locked, "GET", f"/api/scenes?token={VIEW}",
                                         {"Origin": origin})
        assert status == 200 and headers["access-control-allow-origin"] == origin
        assert "Origin" in headers["vary"]
        status, headers = answer_headers(locked, "OPTIONS", "/api/scenes/a/import", {
            "Origin": origin, "Access-Control-Request-Method": "POST",
            "Access-Control-Request-Headers": "authorization, content-type"})
        assert status == 200 and headers["access-control-allow-origin"] == origin
        assert "authorization" in headers["access-control-allow-headers"].lower()
    status, headers = answer_headers(locked, "GET", f"/api/scenes?token={VIEW}",
                                     {"Origin": "https://evil.example"})
    assert "access-control-allow-origin" not in headers
    status, headers = answer_headers(locked, "OPTIONS", "/api/scenes/a/import", {
        "Origin": "https://evil.example", "Access-Control-Request-Method": "POST"})
    assert status == 400 and "access-control-allow-origin" not in headers
