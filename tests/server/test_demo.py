"""`make run`'s demo: three Diggers that the server itself keeps digging."""

import time

import pytest

from ..conftest import start_server, stop_server


@pytest.fixture(scope="module")
def demo_server():
    running = start_server()
    yield running
    stop_server(running)


def test_demo_diggers_are_where_the_manual_puts_them_and_move(demo_server):
    robots = demo_server.get("/api/scenes/default/robots")
    assert [r["position"] for r in robots] == [[0, 0, 1], [0, 0, 0], [0, 0, -1]]
    assert all(r["motors"] == 3 for r in robots)
    first = [demo_server.get(f"/api/scenes/default/robots/{r['id']}")["motors"] for r in robots]
    time.sleep(0.2)
    later = [demo_server.get(f"/api/scenes/default/robots/{r['id']}")["motors"] for r in robots]
    for before, after in zip(first, later):
        assert [m["angle"] for m in before] != [m["angle"] for m in after]
        assert [(m["min"], m["max"]) for m in after] == [(-0.7, 0.7), (-1.6, 0), (-1.6, 0)]
        assert all(m["min"] <= m["angle"] <= m["max"] for m in after)
