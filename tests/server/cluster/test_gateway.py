"""Gateways on a real bus: any gateway serves any scene, whichever worker runs it."""

from __future__ import annotations

import json
import urllib.error

import pytest
import virtual_prosthetics as vp
from websockets.sync.client import connect as ws_connect

from tests.conftest import crash_server, eventually
from tests.server.cluster.conftest import holder, load_balancer


def test_a_script_on_one_gateway_and_a_viewer_on_the_other_see_the_same_scene(cluster, scene_name):
    one, two = cluster.gateways
    script = vp.connect(one.ws, scene=scene_name)
    ball = vp.Ball(0.5)
    viewer = vp.connect(two.ws, scene=scene_name, role="viewer")
    try:
        for x in range(1, 6):  # the script moves it; the viewer's frames follow
            ball.set_position(x, 2, 3)
            script.sync()
            eventually(lambda: viewer.mirror.nodes.get(ball.id, {}).get("position", [0])[0] == x)
        assert holder(cluster.url, scene_name) in ("wa", "wb")
        assert [n["id"] for n in two.nodes(scene_name)] == [ball.id]  # REST on the other gateway
        assert [s["clients"] for s in two.get("/api/scenes") if s["name"] == scene_name] == [1]
    finally:
        script.close()
        viewer.close()


def test_a_bad_message_through_a_gateway_is_answered_and_the_connection_goes_on(cluster, scene_name):
    with ws_connect(f"{cluster.gateways[1].ws}/ws?scene={scene_name}") as socket:
        hello = json.loads(socket.recv())
        json.loads(socket.recv())  # the snapshot
        socket.send("{not json")
        error = next(m for m in map(json.loads, iter(socket.recv, None)) if m["op"] == "error")
        ball = f"{hello['client']}.ball"
        socket.send(json.dumps({"op": "create", "id": 1, "object": ball, "type": "Ball"}))
        answer = next(m for m in map(json.loads, iter(socket.recv, None)) if m.get("id") == 1)
    assert hello["op"] == "hello" and error["code"] == "bad_json"
    assert answer["op"] == "ok" and [n["id"] for n in cluster.gateways[0].nodes(scene_name)] == [ball]


def test_a_recording_started_through_one_gateway_is_seen_and_stopped_through_the_other(cluster, scene_name):
    one, two = cluster.gateways
    script = vp.connect(one.ws, scene=scene_name)
    try:
        vp.Ball(0.5).set_position(1, 2, 3)
        script.sync()
        started = one.post(f"/api/scenes/{scene_name}/recordings")[1]["id"]
        assert {r["id"]: r for r in two.get("/api/recordings")}[started]["state"] == "recording"
        with pytest.raises(urllib.error.HTTPError) as early:  # not half a file
            two.get(f"/api/recordings/{started}")
        assert early.value.code == 409 and json.loads(early.value.read())["code"] == "recording_busy"
        _, held = two.post(f"/api/recordings/{started}/stop")  # a balancer may send it anywhere
    finally:
        script.close()
    assert held["id"] == started and held["stopped"] == "stopped" and held["ticks"] > 0
    for gateway in (one, two):
        listed = {r["id"]: r for r in gateway.get("/api/recordings")}[started]
        assert listed["state"] == "stopped" and listed["stopped"] == "stopped"


def _clients(gateway, scene: str) -> int:
    return sum(s["clients"] for s in gateway.get("/api/scenes") if s["name"] == scene)


def test_a_killed_gateways_clients_reconnect_through_the_other(cluster, scene_name, tmp_path):
    """Last in this module: it kills a gateway."""
    with load_balancer([g.port for g in cluster.gateways], tmp_path) as port:
        script = vp.connect(f"ws://127.0.0.1:{port}", scene=scene_name)
        try:
            ball = vp.Ball(0.5)
            ball.set_position(1, 2, 3)
            script.sync()
            on = next(g for g in cluster.gateways if _clients(g, scene_name) == 1)
            other = next(g for g in cluster.gateways if g is not on)
            crash_server(on)
            try:  # the client reconnects by itself, through the other
                ball.set_position(4, 2, 3)
                script.sync()
            except vp.ConnectionLost:  # sent before the loss was noticed: as a script would,
                ball.set_position(4, 2, 3)  # it sends it again
                script.sync()
            assert _clients(other, scene_name) == 1
            assert [(n["id"], n["position"]) for n in other.nodes(scene_name)] == \
                [(ball.id, [4, 2, 3])]  # the same client: its ball stayed
        finally:
            script.close()
