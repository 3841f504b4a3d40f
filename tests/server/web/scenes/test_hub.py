"""The server's scenes by name (real scene processes, driven without sockets)."""

from __future__ import annotations

import asyncio
import json
import os
import signal
from pathlib import Path

from websockets.sync.client import connect

import virtual_prosthetics as vp
from server.core.protocol.operations import Operations
from server.core.scene.scene import Scene
from server.core.protocol.scene_document import encode_document, export_scene

from server.web.process.messages import Join, Read, Text
from server.web.scenes.hub import Hubs, clients_objects
from server.web.storage.state_dir import StateDir
from tests.conftest import WAIT_SECONDS, eventually, start_server, stop_server
from tests.server.web.storage.test_state_dir import saved_scene


def boxes(count: int) -> str:
    """A client's text making ``count`` boxes."""
    return json.dumps([{"op": "create", "object": f"c7.{k}", "type": "Box"}
                       for k in range(count)])


def test_a_saved_scene_opened_again_while_it_stops_gets_its_last_change(tmp_path: Path) -> None:
    """Stopped less than a second after a change (not in its document yet but on stopping),
    then opened at once: the new process waits for the old one's final save."""
    async def scenario() -> tuple[int, int]:
        hubs = Hubs(state=StateDir(tmp_path))
        try:
            first = hubs.open("lab")
            first.runner.post(Join(1, "c7", "controller", None, True))
            first.runner.post(Text(1, boxes(400)))
            assert json.loads(await first.runner.call(Read(clients_objects))) == 400
            assert await hubs.remove_idle(float("inf")) == ["lab"]
            again = hubs.open("lab")
            held = json.loads(await again.runner.call(Read(clients_objects)))
            return held, again.runner.pid != first.runner.pid
        finally:
            await hubs.stop()
    assert asyncio.run(scenario()) == (400, True)


# --- with a real server ------------------------------------------------------------------

def test_the_owners_of_a_restored_scene_are_never_handed_out_again(tmp_path):
    state = tmp_path / "state"
    saved_scene(state, "lab", "c1001")
    saved_scene(state, "hall", "c1")
    (state / "server.json").write_text("{broken")  # set aside: the count of ids is gone
    server = start_server("--no-demo", "--state-dir", str(state))
    try:
        for scene, owner in (("lab", "c1001"), ("hall", "c1")):
            with connect(f"{server.ws}/ws?scene={scene}") as ws:
                me = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
                assert int(me[1:]) > 1001  # a stranger is nobody the scene knows
                ws.send(json.dumps({"op": "delete", "object": f"{owner}.arm", "id": 1}))
                while (answer := json.loads(ws.recv(timeout=WAIT_SECONDS)))["op"] not in ("ok", "error"):
                    pass
                assert answer["code"] == "forbidden" and owner in answer["message"]
            assert [n["id"] for n in server.nodes(scene)] == [f"{owner}.arm"]
    finally:
        stop_server(server)


def test_a_failed_demo_scene_starts_again_by_itself_and_rest_answers_meanwhile():
    server = start_server("--limit", "leaveGraceSeconds=1")
    try:
        eventually(lambda: server.get("/api/metrics")["scenes"]["default"]["state"] == "running")
        pid = server.get("/api/metrics")["scenes"]["default"]["pid"]
        os.kill(pid, signal.SIGKILL)  # as a crash inside PyBullet would end it
        seen = set()

        def back() -> bool:  # every answer meanwhile is a 200 that says how the scene is
            figures = server.get("/api/metrics")["scenes"]["default"]
            listed = {s["name"]: s for s in server.get("/api/scenes")}
            seen.add(figures["state"])
            assert "default" in listed
            return figures["state"] == "running" and figures["pid"] != pid
        eventually(back)
        assert "failed" in seen or "starting" in seen
        assert len(server.robots("default")) == 6  # the demo's hands are back
        assert server.get("/api/health")["status"] == "ok"
    finally:
        stop_server(server)


def test_a_scene_slow_to_restore_is_not_stopped_as_idle_while_a_client_waits_for_it(tmp_path):
    state = tmp_path / "state"
    scene = Scene("slow")
    operations = Operations(scene, "c5")
    for k in range(40):  # a few seconds to make again
        operations.create(f"c5.{k}", "EdgedHand", [])
        scene.get(f"c5.{k}").keep()
    (state / "scenes").mkdir(parents=True)
    (state / "scenes" / "slow.json").write_bytes(encode_document(export_scene(scene)))
    scene.close()
    server = start_server("--no-demo", "--state-dir", str(state), "--limit", "sceneIdleSeconds=1")
    try:
        with vp.connect(server.ws, scene="slow") as client:  # waited for, never stopped
            assert len(client.mirror.nodes) == len(server.nodes("slow"))
            assert len(server.robots("slow")) == 40
    finally:
        stop_server(server)
