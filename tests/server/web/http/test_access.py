"""Tokens and origins with a real server: controlling needs the token, viewing the view
token, browsers must come from an allowed origin, and no token reaches the log."""

import http.client
import json
import socket
import urllib.error
import urllib.request

import pytest
import trimesh
from websockets.exceptions import InvalidStatus
from websockets.sync.client import connect

import virtual_prosthetics as vp
from server.web.http.access import AccessPolicy
from server.core.kit.errors import Forbidden

from ....conftest import WAIT_SECONDS, start_server, stop_server

CONTROL, VIEW = "s3cret-control", "s3cret-view"


@pytest.fixture(scope="module")
def locked(tmp_path_factory):
    log = tmp_path_factory.mktemp("access") / "server.log"
    running = start_server("--no-demo", "--token", CONTROL, "--view-token", VIEW,
                           "--allow-origin", "https://friend.example", "--allow-host",
                           "lab.example", "--log-level", "info", log=log)
    running.log = log
    yield running
    stop_server(running)


def first_message(server, query, origin=None):
    headers = {"Origin": origin} if origin else {}
    with connect(f"{server.ws}/ws?{query}", additional_headers=headers) as ws:
        return json.loads(ws.recv(timeout=WAIT_SECONDS))


@pytest.mark.parametrize("query, allowed", [
    ("scene=a&role=controller", False),
    ("scene=a&role=controller&token=wrong", False),
    (f"scene=a&role=controller&token={VIEW}", False),
    (f"scene=a&role=controller&token={CONTROL}", True),
    ("scene=a&role=viewer", False),
    (f"scene=a&role=viewer&token={VIEW}", True),
    (f"scene=a&role=viewer&token={CONTROL}", True),
])
def test_each_role_needs_its_token(locked, query, allowed):
    message = first_message(locked, query)
    if allowed:
        assert message["op"] == "hello"
    else:
        assert message["op"] == "error" and message["code"] == "forbidden"
        assert "token" in message["message"] and CONTROL not in json.dumps(message)


@pytest.mark.parametrize("origin, allowed", [
    (None, True),  # a script, not a browser
    ("https://friend.example", True),
    ("https://evil.example", False),
    # a server on loopback takes pages of any loopback origin: a user's own folder
    ("http://127.0.0.1:8080", True), ("http://localhost:5173", True), ("http://[::1]:9000", True),
    ("http://127.0.0.1.evil.example", False), ("null", False),  # a file, a sandboxed frame
])
def test_browser_pages_must_come_from_an_allowed_origin(locked, origin, allowed):
    message = first_message(locked, f"scene=a&role=viewer&token={VIEW}", origin)
    assert (message["op"] == "hello") is allowed
    if not allowed:  # the refusal says how to allow the page
        assert f"--allow-origin {origin}" in message["message"]
        assert f"VP_ALLOWED_ORIGINS={origin}" in message["message"]
    own = first_message(locked, f"scene=a&role=viewer&token={VIEW}", locked.http)
    assert own["op"] == "hello"  # the server's own pages


def test_rest_changes_need_the_control_token(locked):
    request = urllib.request.Request(f"{locked.http}/api/assets?token={VIEW}", data=b"glb?",
                                     method="POST")
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(request, timeout=WAIT_SECONDS)
    assert refused.value.code == 403 and json.loads(refused.value.read())["code"] == "forbidden"
    request.add_header("Authorization", f"Bearer {CONTROL}")
    with pytest.raises(urllib.error.HTTPError) as judged:  # let in: then judged as a file
        urllib.request.urlopen(request, timeout=WAIT_SECONDS)
    assert judged.value.code == 400


def test_the_python_client_controls_with_the_token_and_the_log_never_shows_it(locked):
    with vp.Session(locked.ws, scene="tokened", token=CONTROL) as scene:
        robot = vp.Robot(scene=scene)
        scene.sync()
        robots = locked.get(f"/api/scenes/tokened/robots?token={VIEW}")
        assert robot.id in {r["id"] for r in robots}
    first_message(locked, f"scene=a&role=controller&token={CONTROL}")
    text = locked.log.read_text()
    assert "/ws?" in text and "token=***" in text  # request lines are logged, blanked
    assert CONTROL not in text and VIEW not in text


def test_a_script_uploads_with_its_token(locked):
    data = trimesh.creation.icosphere(1, 0.2).export(file_type="glb")
    with vp.connect(locked.ws, scene="uploads", token=CONTROL) as scene:
        name = vp.upload_asset(data)
        vp.GLTFPart(name)
        scene.sync()
    with vp.connect(locked.ws, scene="uploads", token=CONTROL) as scene:
        scene.token = None  # as a script that was given no token would send
        with pytest.raises(vp.ServerError) as refused:
            vp.upload_asset(data + b" ")
        assert refused.value.code == "forbidden"


def test_a_policy_without_tokens_lets_everyone_in():
    open_policy = AccessPolicy()
    open_policy.check_role("controller", None)
    open_policy.check_change(None)
    with pytest.raises(Forbidden):
        open_policy.check_origin("https://evil.example", "127.0.0.1:8000")


def test_rest_reads_need_the_view_token_but_health_does_not(locked):
    assert locked.get("/api/health")["status"] == "ok"
    with pytest.raises(urllib.error.HTTPError) as refused:
        locked.get("/api/scenes")
    assert refused.value.code == 403
    assert locked.get(f"/api/scenes?token={VIEW}")
    request = urllib.request.Request(f"{locked.http}/api/metrics",
                                     headers={"Authorization": f"Bearer {CONTROL}"})
    with urllib.request.urlopen(request, timeout=WAIT_SECONDS) as answer:
        assert "scenes" in json.loads(answer.read())


def raw(server, method: str, path: str, headers: dict, body: bytes | None = None):
    """Status and JSON body of a request sent exactly so (Host included)."""
    connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=WAIT_SECONDS)
    try:
        connection.putrequest(method, path, skip_host=True)
        for name, value in {"Content-Length": str(len(body or b"")), **headers}.items():
            connection.putheader(name, value)
        connection.endheaders(body)
        answer = connection.getresponse()
        return answer.status, json.loads(answer.read() or b"null")
    finally:
        connection.close()


def test_a_page_of_another_site_cannot_import_or_upload_even_on_an_open_server(server):
    before = server.nodes("default")
    document = json.dumps({"format": "virtual-prosthetics-scene"}).encode()
    for path in ("/api/scenes/default/import", "/api/assets"):
        status, error = raw(server, "POST", path, {
            "Host": f"127.0.0.1:{server.port}", "Origin": "https://evil.example",
            "Content-Type": "text/plain"}, document)  # a form needs no preflight
        assert (status, error["code"]) == (403, "forbidden") and "evil.example" in error["message"]
    assert server.nodes("default") == before


def test_a_name_the_server_does_not_answer_to_is_refused_dns_rebinding(locked):
    evil = f"rebind.evil.example:{locked.port}"
    status, error = raw(locked, "GET", f"/api/scenes?token={VIEW}", {"Host": evil})
    assert (status, error["code"]) == (403, "forbidden")
    assert "--allow-host rebind.evil.example" in error["message"]
    with pytest.raises(InvalidStatus) as refused:  # the handshake itself, as a controller
        connect(f"ws://{evil}/ws?scene=a&token={CONTROL}", origin=f"http://{evil}",
                sock=socket.create_connection(("127.0.0.1", locked.port))).close()
    assert refused.value.response.status_code == 403
    for allowed in (f"lab.example:{locked.port}", f"localhost:{locked.port}", "[::1]:1"):
        assert raw(locked, "GET", f"/api/scenes?token={VIEW}", {"Host": allowed})[0] == 200


def test_resume_keys_never_reach_the_log(locked):
    with connect(f"{locked.ws}/ws?scene=resumed&token={CONTROL}") as ws:
        key = json.loads(ws.recv(timeout=WAIT_SECONDS))["resume"]
    with connect(f"{locked.ws}/ws?scene=resumed&token={CONTROL}&resume={key}") as ws:
        assert json.loads(ws.recv(timeout=WAIT_SECONDS))["resume"] == key  # the same client again
    text = locked.log.read_text()
    assert "resume=***" in text and key not in text and key.split(":")[1] not in text


@pytest.mark.parametrize("address, allowed", [
    ("127.0.0.1", True), ("::1", True), ("localhost", True), ("0.0.0.0", False),
    ("192.168.1.5", False)])
def test_loopback_pages_are_allowed_only_by_a_server_on_loopback(address, allowed):
    policy = AccessPolicy.serving(address)
    assert policy.allows_origin("http://127.0.0.1:8080") is allowed
    assert policy.allows_origin("http://localhost:3000") is allowed
    assert not policy.allows_origin("https://evil.example")
