"""A scene's ticks handed to its connections: the same frames to every viewer, in order
with each connection's answers, and what handing them out costs in /api/metrics."""

import json

import httpx
from websockets.sync.client import connect

from tests.conftest import WAIT_SECONDS, eventually

from ..ws_requests import next_message, request_all


def frames(ws, count):
    """How many of the next ``count`` messages are frames."""
    return sum(json.loads(ws.recv(timeout=WAIT_SECONDS))["op"] == "frame" for _ in range(count))


def test_every_viewer_gets_the_same_frames_in_order(server, scene_name):
    viewers = [connect(f"{server.ws}/ws?scene={scene_name}&role=viewer").__enter__()
               for _ in range(12)]
    try:
        for viewer in viewers:
            next_message(viewer, "snapshot")
        seen = [[] for _ in viewers]
        for _ in range(30):
            for mine, viewer in zip(seen, viewers):
                mine.append(viewer.recv(timeout=WAIT_SECONDS))
        by_seq = [{json.loads(text)["seq"]: text for text in mine} for mine in seen]
        for mine in by_seq:
            assert sorted(mine) == list(mine)  # in order
        common = set.intersection(*(set(mine) for mine in by_seq))
        assert len(common) >= 20  # the viewers joined within a few ticks of each other
        for seq in common:
            assert len({mine[seq] for mine in by_seq}) == 1  # the very same text
    finally:
        for viewer in viewers:
            viewer.close()


def test_answers_and_frames_never_overtake_each_other(server, scene_name):
    with connect(f"{server.ws}/ws?scene={scene_name}") as ws:
        me = json.loads(ws.recv(timeout=WAIT_SECONDS))["client"]
        request_all(ws, [{"op": "create", "object": f"{me}.m", "type": "MotorZ"}])
        for k in range(50):  # answers are queued or written at once, frames likewise
            ws.send(json.dumps({"op": "call", "id": k, "object": f"{me}.m",
                                "method": "setAngle", "args": [k / 100]}))
        ids, seqs = [], []
        while len(ids) < 50:
            message = json.loads(ws.recv(timeout=WAIT_SECONDS))
            if message["op"] == "ok":
                ids.append(message["id"])
            elif message["op"] == "frame":
                seqs.append(message["seq"])
        assert ids == list(range(50)) and seqs == sorted(seqs)


def test_metrics_count_the_frames_handed_out_and_their_cost(server, scene_name):
    def figures():
        found = httpx.get(f"{server.http}/api/metrics", timeout=WAIT_SECONDS).json()
        return found["scenes"][scene_name]

    with connect(f"{server.ws}/ws?scene={scene_name}&role=viewer", max_queue=None) as one, \
            connect(f"{server.ws}/ws?scene={scene_name}&role=viewer", max_queue=None) as two:
        next_message(one, "frame")
        next_message(two, "frame")
        before = figures()
        # (frames go straight into the sockets, so what is read may have been sent before:
        # the figures are taken once the scene has ticked enough, whatever was read)
        eventually(lambda: figures()["ticks"] - before["ticks"] >= 20)
        frames(one, 5)
        frames(two, 5)
        after = figures()
    ticks = after["ticks"] - before["ticks"]
    handed = after["viewerFrames"] - before["viewerFrames"]
    assert ticks >= 20 and abs(handed - 2 * ticks) <= 6  # a frame a tick to each viewer
    assert after["fanoutCpuSeconds"] > before["fanoutCpuSeconds"]
