"""A gateway's scenes on a real bus whose workers are full: a newcomer is refused at once
with the limit that refused it (which limit, its value, the flag that changes it, and each
worker's reason), as a single server refuses past ``--limit scenes``; nothing else waits."""

from __future__ import annotations

import json
from typing import Any, Iterator

import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect as ws_connect

from tests.server.cluster.conftest import Cluster, holder, running_bus
from tests.conftest import WAIT_SECONDS

TRY_AGAIN_LATER = 1013


@pytest.fixture(scope="module")
def small_cluster(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Cluster]:
    """Two workers that run one scene each, and one gateway (whose default scene takes
    one of the two)."""
    folder = tmp_path_factory.mktemp("cluster")
    with running_bus(folder) as url:
        running = Cluster(url, folder, gateways=1, worker_extra=("--limit", "scenes=1"))
        yield running
        running.close()


def _first_messages(socket: Any, count: int) -> list[dict[str, Any]]:
    return [json.loads(socket.recv(timeout=WAIT_SECONDS)) for _ in range(count)]


def test_a_scene_no_worker_has_room_for_is_refused_at_once_naming_the_limit(small_cluster, scene_name):
    gateway = small_cluster.gateways[0]
    with ws_connect(f"{gateway.ws}/ws?scene={scene_name}a") as first:
        [hello] = _first_messages(first, 1)
        assert hello["op"] == "hello", hello
        # the gateway's default scene runs on one worker, this one on the other
        assert {holder(small_cluster.url, name) for name in ("default", f"{scene_name}a")} == \
            {"wa", "wb"}
        with ws_connect(f"{gateway.ws}/ws?scene={scene_name}b") as refused:
            # well within the 30 s a scene waits for a worker that may still come
            [refusal] = _first_messages(refused, 1)
            with pytest.raises(ConnectionClosed) as closed:
                refused.recv(timeout=WAIT_SECONDS)
        ball = json.dumps({"op": "create", "id": 1, "object": f"{hello['client']}.ball",
                           "type": "Ball"})
        first.send(ball)  # the scenes already placed carry on
        answer = next(m for m in map(json.loads, iter(lambda: first.recv(timeout=WAIT_SECONDS), None))
                      if m.get("id") == 1)
    assert refusal["op"] == "error" and refusal["code"] == "limit_exceeded"
    assert refusal["details"] == {"limit": "scenes", "value": 1, "flag": "--limit scenes=N",
                                  "scene": f"{scene_name}b"}
    assert "wa: it runs its maximum of 1 scenes" in refusal["message"]
    assert "wb: it runs its maximum of 1 scenes" in refusal["message"]
    assert closed.value.rcvd is not None and closed.value.rcvd.code == TRY_AGAIN_LATER
    assert answer["op"] == "ok" and holder(small_cluster.url, f"{scene_name}b") is None
    # it never ran: neither listed nor reported as a failed scene
    assert f"{scene_name}b" not in [s["name"] for s in gateway.get("/api/scenes")]
    assert not any(f"{scene_name}b" in problem for problem in gateway.get("/api/health")["problems"])
