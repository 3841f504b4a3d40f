"""Workers on a real bus: a dead worker's scenes come back on another from what was saved,
with their clients."""

from __future__ import annotations

import virtual_prosthetics as vp

from tests.conftest import eventually
from tests.server.cluster.conftest import holder


def test_a_killed_workers_scene_comes_back_on_the_other_with_its_objects(cluster, scene_name):
    one, two = cluster.gateways
    script = vp.connect(one.ws, scene=scene_name)
    ball = vp.Ball(0.5)
    ball.set_position(1, 2, 3)
    script.sync()  # acknowledged: journaled on the shared state folder
    viewer = vp.connect(two.ws, scene=scene_name, role="viewer")
    try:
        first = holder(cluster.url, scene_name)
        cluster.kill_worker(first)
        eventually(lambda: holder(cluster.url, scene_name) not in (None, first), timeout=30)
        refusals = _sync_until_answered(script)  # it reconnects by itself
        assert {error.code for error in refusals} <= {"unknown_scene"}  # "failed; reconnect"
        ball.set_position(4, 2, 3)
        script.sync()
        eventually(lambda: viewer.mirror.nodes.get(ball.id, {}).get("position") == [4, 2, 3],
                   timeout=10)  # the viewer came back too
        assert [n["id"] for n in two.nodes(scene_name)] == [ball.id]
    finally:
        script.close()
        viewer.close()


def _sync_until_answered(session: vp.Session) -> list[vp.ServerError]:
    refusals = []
    for _ in range(50):
        try:
            session.sync()
            return refusals
        except vp.ServerError as error:
            refusals.append(error)
    raise AssertionError(f"never answered: {refusals[-3:]}")
