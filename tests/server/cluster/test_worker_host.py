"""Workers on a real bus: scenes spread over them, and a dead worker's scenes come back on
another from what was saved, with their clients."""

from __future__ import annotations

import virtual_prosthetics as vp

from server.cluster.bus import PLACE
from tests.conftest import eventually
from tests.server.cluster.conftest import ask_bus, holder


def _loads(url: str) -> dict[str, int]:
    async def gather(bus):
        return {name: scenes for name, scenes, most in await bus.gather(PLACE, None, 0.2)}
    return ask_bus(url, gather)


def test_new_scenes_go_to_the_least_busy_worker(cluster, scene_name):
    viewers = [vp.connect(cluster.gateways[k % 2].ws, scene=f"{scene_name}n{k}", role="viewer")
               for k in range(6)]
    try:
        loads = _loads(cluster.url)
        assert sorted(loads) == ["wa", "wb"] and abs(loads["wa"] - loads["wb"]) <= 1
        assert {holder(cluster.url, f"{scene_name}n{k}") for k in range(6)} == {"wa", "wb"}
    finally:
        for viewer in viewers:
            viewer.close()


def test_a_killed_workers_scene_comes_back_on_the_other_with_its_objects(cluster, scene_name):
    """Last in this module: it kills a worker."""
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
