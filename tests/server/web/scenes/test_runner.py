"""Scenes in their own processes: one scene's flood or crash never stops another scene."""

import asyncio
import json
import os
import signal
import threading
import time

import pytest
from websockets.exceptions import ConnectionClosed

from server.core.physics.assets import AssetLibrary
from server.core.kit.limits import DEFAULT
from server.web.process.messages import Join, Text
from server.web.scenes.runner import SceneRunner
from server.web.storage.scene_store import SceneStore
from tests.conftest import WAIT_SECONDS, start_server, stop_server, unwritable

from ..http.test_socket import open_client
from ..ws_requests import next_message


def test_a_flooded_scene_does_not_stop_another_scenes_frames(server, scene_name):
    watcher, _, _ = open_client(server, scene_name + "w", "viewer")
    flooder, hello, _ = open_client(server, scene_name + "f")
    me = hello["client"]
    seen: list[tuple[int, bool]] = []  # (frame seq, whether the flood was answered yet)
    answered = threading.Event()

    def watch():
        while len(seen) < 10_000:
            try:
                message = json.loads(watcher.recv(timeout=WAIT_SECONDS))
            except Exception:
                return
            if message["op"] == "frame":
                seen.append((message["seq"], answered.is_set()))
            if answered.is_set() and sum(done for _, done in seen) >= 3:
                return
    with watcher, flooder:
        next_message(watcher, "frame")
        reader = threading.Thread(target=watch)
        reader.start()
        flooder.send(json.dumps({"op": "batch", "id": 1, "ops": [
            {"op": "create", "object": f"{me}.{k}", "type": "EdgedHand"} for k in range(100)]}))
        answer = next_message(flooder, "ok", timeout=60)
        answered.set()
        reader.join(timeout=WAIT_SECONDS)
        assert answer["id"] == 1 and len(server.get(f"/api/scenes/{scene_name}f/robots")) == 100
    during = [seq for seq, done in seen if not done]
    # while the flooded scene applied 7 300 objects, the other scene kept sending frames
    assert len(during) >= 5 and during == sorted(set(during))


def test_a_scene_whose_process_dies_takes_no_other_scene_with_it(server, scene_name):
    doomed, hello, _ = open_client(server, scene_name + "d")
    other, other_hello, _ = open_client(server, scene_name + "o")
    with doomed, other:
        other.send(json.dumps({"op": "create", "object": f"{other_hello['client']}.b",
                               "type": "Box", "id": 1}))
        assert next_message(other, "ok")["id"] == 1
        pid = server.get("/api/metrics")["scenes"][scene_name + "d"]["pid"]
        os.kill(pid, signal.SIGKILL)  # as a crash inside PyBullet would end it
        farewell = next_message(doomed, "error")
        assert farewell["code"] == "unknown_scene" and "failed" in farewell["message"]
        with pytest.raises(ConnectionClosed):
            doomed.recv(timeout=WAIT_SECONDS)
        seqs = [next_message(other, "frame")["seq"] for _ in range(5)]
        assert seqs == sorted(set(seqs))
        assert [n["id"] for n in server.nodes(f"{scene_name}o")] == [
            f"{other_hello['client']}.b"]
    again, _, snapshot = open_client(server, scene_name + "d")  # the scene starts afresh
    with again:
        assert snapshot["nodes"] == [] and next_message(again, "frame")


def _running(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().split(") ", 1)[1][0] != "Z"  # a zombie has ended
    except FileNotFoundError:
        return False


def test_scene_processes_end_when_the_server_is_killed(scene_name):
    server = start_server("--no-demo")
    try:
        busy, hello, _ = open_client(server, scene_name + "b")
        me = hello["client"]
        with busy:  # a scene whose ticks all run late (overlapping hands) must hear it too
            busy.send(json.dumps({"op": "batch", "id": 1, "ops": [
                {"op": "create", "object": f"{me}.{k}", "type": "EdgedHand"} for k in range(100)]}))
            assert next_message(busy, "ok", timeout=60)["id"] == 1
            pids = [s["pid"] for s in server.get("/api/metrics")["scenes"].values()]
            assert len(pids) == 2 and all(_running(pid) for pid in pids)
            server.process.kill()  # no goodbye: as an out-of-memory kill would end it
            server.process.wait(timeout=WAIT_SECONDS)
            deadline = time.monotonic() + WAIT_SECONDS
            while any(_running(pid) for pid in pids) and time.monotonic() < deadline:
                time.sleep(0.1)
            assert not any(_running(pid) for pid in pids), "scene processes outlived the server"
    finally:
        if server.process.poll() is None:
            stop_server(server)


def test_how_a_scene_process_ended_is_read_once_however_many_wait_for_it(tmp_path):
    """A scene that stops with changes it could not save says so by its exit code, and
    every waiter (the server stopping, a successor scene, its own reader) sees that code.
    Found by CI: the reader and the server's stop both waited on the process, one of them
    read the fork server's report of its end and the other an empty pipe (code 255), and
    the server exited 0 with a scene's changes lost."""
    def ended(runner: SceneRunner) -> None:
        runner.post(Join(1, "c1", "controller"))
        runner.post(Text(1, json.dumps({"op": "create", "id": 1, "object": "c1.b",
                                         "type": "Box", "args": [0.1]})))
        runner.stop()
        waiters = [threading.Thread(target=runner.join, args=(20,)) for _ in range(4)]
        for waiter in waiters:
            waiter.start()
        for waiter in waiters:
            waiter.join()

    async def stop_scenes() -> list[bool]:
        results = []
        for k in range(6):
            runner = SceneRunner(f"s{k}", DEFAULT, 60.0, AssetLibrary(), None, lambda events: None,
                                 SceneStore(tmp_path / "scenes" / f"s{k}.json"))
            runner.start()
            await asyncio.to_thread(ended, runner)
            results.append(runner.unsaved)
        return results

    (tmp_path / "scenes").mkdir()
    with unwritable(tmp_path / "scenes"):  # no journal can be made: the box is never kept
        assert asyncio.run(stop_scenes()) == [True] * 6
