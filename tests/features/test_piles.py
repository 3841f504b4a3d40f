"""A dynamic scene given a pile keeps answering and its viewers keep getting frames."""

import json
import math

from websockets.sync.client import connect

from tests.conftest import WAIT_SECONDS
from tests.server.web.ws_requests import next_message, request_all


def test_five_hundred_balls_made_in_one_spot_are_answered_and_the_scene_keeps_ticking(server, scene_name):
    # 100 balls made at one point in one batch left a scene without an answer to a ping
    # for 60 s; 1 900 took it to 3.27 GB and it never answered
    url = f"{server.ws}/ws?scene={scene_name}"
    # (the maker reads no frames after its requests: unqueued, they would hold its close
    # behind them for the close timeout)
    with connect(url, max_size=None, max_queue=None) as maker, \
            connect(url + "&role=viewer", max_size=None) as viewer:
        me = json.loads(maker.recv(timeout=WAIT_SECONDS))["client"]
        maker.recv(timeout=WAIT_SECONDS)
        for _ in range(2):
            viewer.recv(timeout=WAIT_SECONDS)
        request_all(maker, [{"op": "call", "object": "scene", "method": "setPhysics",
                             "args": ["dynamic"]}])
        ops = []
        for i in range(500):
            ops += [{"op": "create", "object": f"{me}.{i}", "type": "Ball", "args": [0.2]},
                    {"op": "call", "object": f"{me}.{i}", "method": "setPosition", "args": [0, 2, 0]}]
        request_all(maker, [{"op": "batch", "ops": ops}])
        request_all(maker, [{"op": "call", "object": "scene", "method": "getTime"}])
        seen: dict[str, list[float]] = {}
        for _ in range(30):  # frames keep coming, and they carry the balls apart
            frame = next_message(viewer, "frame")
            seen.update((i, pose[:3]) for i, pose in frame.get("poses", {}).items())
        assert len(seen) == 500
        spots = list(seen.values())
        assert min(math.dist(a, b) for k, a in enumerate(spots) for b in spots[k + 1:]) > 0.3
