"""REST inspection against a real server."""

import contextlib
import http.client
import json
import os
import signal
import time
import urllib.error
import urllib.request

import pytest
from websockets.sync.client import connect

from server.core.protocol.operations import Operations
from server.core.scene.scene import Scene
from server.core.protocol.scene_document import encode_document, export_scene
from tests.conftest import WAIT_SECONDS, crash_server, eventually, start_server, stop_server

from ..ws_requests import request_all, wait_ticks

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first


def test_health(server):
    health = server.get("/api/health")
    assert health["status"] == "ok" and health["protocol"] == 1


def test_robot_report_lists_motors_in_order(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        client = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
        request_all(ws, [
            {"op": "create", "object": f"{client}.1", "type": "EdgedHand", "args": [False]},
            {"op": "call", "object": f"{client}.1", "method": "setPosition", "args": [1, 2, 3]},
            {"op": "call", "object": f"{client}.1", "method": "flexFinger", "args": [2, 0.4]},
        ])
        robots = server.get(f"/api/scenes/{scene_name}/robots")
        assert robots == [{"id": f"{client}.1", "type": "EdgedHand", "name": None, "owner": client,
                           "shared": False, "position": [1, 2, 3],
                           "visible": True, "motors": 20, "parts": 36}]
        report = server.get(f"/api/scenes/{scene_name}/robots/{client}.1")
        motors = report["motors"]
        assert [m["index"] for m in motors] == list(range(20))
        assert {"id", "index", "type", "axis", "min", "max", "angle", "name", "flipped",
                "follows"} <= set(motors[0])
        assert [m["angle"] for m in motors[9:12]] == [-0.4] * 3
        assert motors[0]["type"] == "MotorX" and motors[0]["flipped"] is False
        palm = report["parts"][0]
        assert palm["type"] == "EdgedPalm" and palm["world"]["position"] == [1, 2, 3]
        summary = server.get(f"/api/scenes/{scene_name}")
        assert summary["robots"] == 1 and summary["clients"] == 1
        assert (summary["viewers"], summary["controllers"]) == (0, 1)
        snapshot = server.get(f"/api/scenes/{scene_name}/snapshot")
        assert len(snapshot["nodes"]) == summary["objects"]


def test_infinite_limits_are_strings_in_rest(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        client = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
        request_all(ws, [
            {"op": "create", "object": f"{client}.1", "type": "Robot"},
            {"op": "create", "object": f"{client}.2", "type": "MotorY"},
            {"op": "call", "object": f"{client}.1", "method": "attachChain",
             "args": [{"ref": f"{client}.2"}]},
        ])
        [motor] = server.get(f"/api/scenes/{scene_name}/robots/{client}.1")["motors"]
        assert (motor["min"], motor["max"]) == ("-Infinity", "Infinity")


def test_a_robot_downloads_as_a_urdf_zip_and_a_glb(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        client = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
        hand = f"{client}.1"
        request_all(ws, [{"op": "create", "object": hand, "type": "AnthroHand", "args": [True]}])
        for kind, media, check in (("urdf", "application/zip", lambda b: b[:2] == b"PK"),
                                   ("glb", "model/gltf-binary", lambda b: b[:4] == b"glTF")):
            url = f"{server.http}/api/scenes/{scene_name}/robots/{hand}/{kind}"
            with urllib.request.urlopen(url, timeout=WAIT_SECONDS) as answer:
                body = answer.read()
                assert answer.headers["Content-Type"] == media and check(body)
                suffix = "zip" if kind == "urdf" else "glb"
                assert answer.headers["Content-Disposition"] == f'attachment; filename="{hand}.{suffix}"'


def test_sensor_readings_and_contacts(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        client = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
        finger, sensor, box = (f"{client}.{name}" for name in ("finger", "sensor", "box"))
        request_all(ws, [
            {"op": "create", "object": finger, "type": "EdgedFinger"},
            {"op": "call", "object": finger, "method": "setPosition", "args": [0, 0.5, 0]},
            {"op": "create", "object": sensor, "type": "Sensor"},
            {"op": "call", "object": sensor, "method": "attachToSlot", "args": [{"ref": finger}]},
            {"op": "create", "object": box, "type": "Box", "args": [1, 0.1, 0.1]},
            {"op": "call", "object": box, "method": "setPosition", "args": [0, 2, 0]},
        ])
        reading = server.get(f"/api/scenes/{scene_name}/sensors/{sensor}?other={box}")
        assert reading == {"id": sensor, "type": "Sensor", "part": finger, "watched": False,
                           "laserColor": None, "distance": pytest.approx(0.45),
                           "touch": 0.0, "position": [0, 1.5, 0], "objects": [], "force": 0.0,
                           "contacts": [],
                           "collision": False, "object": False}
        request_all(ws, [{"op": "call", "object": box, "method": "setPosition",
                          "args": [0, 1.5, 0]}])
        reading = server.get(f"/api/scenes/{scene_name}/sensors/{sensor}?other={box}")
        assert reading["objects"] == [box] and reading["collision"] and reading["object"]
        assert reading["distance"] == "Infinity"  # the box is around the sensor now
        wait_ticks(ws)
        contacts = server.get(f"/api/scenes/{scene_name}/contacts")["contacts"]
        assert contacts == [[box, finger]]
        with pytest.raises(urllib.error.HTTPError) as caught:
            server.get(f"/api/scenes/{scene_name}/sensors/{finger}")  # a part, not a sensor
        assert caught.value.code == 404


def test_openapi_documents_the_routes(server):
    paths = server.get("/openapi.json")["paths"]
    for path in ("/api/health", "/api/scenes", "/api/scenes/{scene}/robots/{robot_id}"):
        assert path in paths


def test_metrics_report_ticks_of_a_watched_scene_and_do_not_wake_a_sleeping_one(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}&role=viewer") as ws:
        ws.recv(timeout=WAIT_SECONDS)
        first = server.figures(scene_name)["ticks"]
        time.sleep(0.2)
        assert server.figures(scene_name)["ticks"] > first
    eventually(lambda: server.get("/api/metrics")["scenes"][scene_name]["asleep"])
    asleep = server.get("/api/metrics")["scenes"][scene_name]
    time.sleep(0.2)
    again = server.get("/api/metrics")["scenes"][scene_name]
    assert again["asleep"] and again["ticks"] == asleep["ticks"]


def test_metrics_give_recent_tick_percentiles_and_request_rates(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        client = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
        request_all(ws, [{"op": "create", "object": f"{client}.r", "type": "Robot"}]
                    + [{"op": "call", "object": f"{client}.r", "method": "setPosition",
                        "args": [[n / 100, 0, 0]]} for n in range(200)])
        figures = server.get("/api/metrics")["scenes"][scene_name]
    assert figures["requests"] == 201
    assert figures["requestsPerSecond"] > 0
    assert figures["tickMsP50"] <= figures["tickMsP95"] <= figures["tickMsMax"]
    assert 0 < figures["ticksPerSecond"] and figures["windowSeconds"] > 0
    assert 0 <= figures["cpuPercent"] and figures["cpuSeconds"] > 0


def test_metrics_in_prometheus_text(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}&role=viewer") as ws:
        ws.recv(timeout=WAIT_SECONDS)
        eventually(lambda: server.figures(scene_name)["ticks"] > 0)
        with urllib.request.urlopen(f"{server.http}/api/metrics?format=prometheus", timeout=WAIT_SECONDS) as response:
            assert response.headers["Content-Type"].startswith("text/plain; version=0.0.4")
            lines = response.read().decode().splitlines()
    ticks = next(line for line in lines if line.startswith(f'vp_ticks_total{{scene="{scene_name}"}}'))
    assert float(ticks.split()[-1]) > 0
    assert "# TYPE vp_tick_ms_p95 gauge" in lines
    with pytest.raises(urllib.error.HTTPError) as caught:
        server.get("/api/metrics?format=xml")
    assert caught.value.code == 422
    assert "format" in json.loads(caught.value.read())["detail"][0]["loc"]


def test_robots_with_unlimited_motors_report_and_impossible_limits_are_refused(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        me = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
        request_all(ws, [
            {"op": "create", "object": f"{me}.1", "type": "Robot"},
            {"op": "create", "object": f"{me}.2", "type": "MotorZ"},
            {"op": "call", "object": f"{me}.2", "method": "attachToSlot",
             "args": [{"ref": f"{me}.1"}]},
            {"op": "call", "object": f"{me}.2", "method": "setAngle", "args": [1e9]},
        ])
        ws.send(json.dumps({"op": "create", "id": 5, "object": f"{me}.3", "type": "MotorZ",
                            "args": ["Infinity", "Infinity"]}))
        while (answer := json.loads(ws.recv(timeout=WAIT_SECONDS)))["op"] not in ("ok", "error"):
            pass
        assert answer["code"] == "out_of_range" and "no finite angle" in answer["message"]
        [motor] = server.get(f"/api/scenes/{scene_name}/robots/{me}.1")["motors"]
        assert (motor["min"], motor["max"], motor["angle"]) == ("-Infinity", "Infinity", 1e9)
        with pytest.raises(urllib.error.HTTPError) as missing:
            server.get(f"/api/scenes/{scene_name}/robots/{me}.3")
        assert missing.value.code == 404


def test_deeply_nested_json_to_import_is_a_structured_error(server, scene_name):
    request = urllib.request.Request(f"{server.http}/api/scenes/{scene_name}/import",
                                     data=b"[" * 200_000 + b"]" * 200_000, method="POST")
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(request, timeout=WAIT_SECONDS)
    assert refused.value.code == 400 and refused.value.headers["Content-Type"] == "application/json"
    assert json.loads(refused.value.read())["code"] == "bad_json"
    assert scene_name not in [s["name"] for s in server.get("/api/scenes")]  # none left behind


def cpu_seconds(pid: int) -> float:
    """User and system CPU a process has used so far."""
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def test_a_large_import_is_read_and_checked_in_its_scenes_process_not_the_servers(scene_name):
    scene = Scene("big")
    operations = Operations(scene, "c5")
    for k in range(9_000):
        operations.create(f"c5.{k}", "Robot", [])
    document = encode_document(export_scene(scene))
    scene.close()
    server = start_server("--no-demo")
    try:
        connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=60)
        connection.request("POST", f"/api/scenes/{scene_name}/import", body=b"{}")
        connection.getresponse().read()  # the scene's process exists (the document refused)
        before = cpu_seconds(server.process.pid)
        connection.request("POST", f"/api/scenes/{scene_name}/import", body=document)
        answer = connection.getresponse()
        assert answer.status == 200 and json.loads(answer.read())["objects"] == 9_000
        spent = cpu_seconds(server.process.pid) - before
        # parsing and checking it took ~0.15 s of CPU here, sending it on as objects more;
        # now the server's own process only moves its bytes (~0.02 s)
        assert spent < 0.1, f"the server's own process spent {spent:.2f} s on the import"
    finally:
        stop_server(server)


def test_a_stopped_scene_is_marked_as_such_and_holds_up_no_list(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        json.loads(ws.recv(timeout=WAIT_SECONDS))
        pid = server.get("/api/metrics")["scenes"][scene_name]["pid"]
        os.kill(pid, signal.SIGSTOP)
        try:
            def marked() -> bool:  # answered while the scene is stopped: it was not waited for
                figures = server.get("/api/metrics")["scenes"]
                listed = {s["name"]: s for s in server.get("/api/scenes")}
                assert figures["default"]["state"] == "running"
                return figures[scene_name]["state"] == listed[scene_name]["state"] == "unresponsive"
            eventually(marked)
            health = server.get("/api/health")
            assert health["status"] == "degraded"
            assert any(f"scene {scene_name} has sent nothing" in p for p in health["problems"])
        finally:
            os.kill(pid, signal.SIGCONT)
        eventually(lambda: server.get("/api/metrics")["scenes"][scene_name]["state"] == "running")


def test_a_scene_working_through_a_backlog_still_gives_its_figures_at_once(scene_name):
    server = start_server("--no-demo", "--limit",
                          "bytesPerSecond=1000000000")
    try:
        with contextlib.ExitStack() as stack:
            for _ in range(3):  # each may have 4 MiB of text waiting on the scene
                ws = stack.enter_context(connect(f"{server.ws}/ws?scene={scene_name}",
                                                 max_size=None, close_timeout=0.5))
                me = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
                request_all(ws, [{"op": "create", "object": f"{me}.h", "type": "EdgedHand"}])
                text = json.dumps([{"op": "call", "object": f"{me}.h", "method": "flexFingers",
                                    "args": [k / 1000]} for k in range(1000)])
                for _ in range(45):  # seconds of work, none answered yet
                    ws.send(text)
            figures = server.get("/api/metrics")["scenes"][scene_name]
            assert figures["state"] == "running" and "tickMsP95" in figures  # fresh, not none
            assert figures["requests"] < 3 * 45_000  # asked and answered amid the backlog
            crash_server(server)  # a graceful stop (or close) would wait for the backlog
    finally:
        if server.process.poll() is None:
            crash_server(server)
