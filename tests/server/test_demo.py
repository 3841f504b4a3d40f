"""`make run`'s demos: six hands gesturing (default) and three Diggers that keep digging."""

import time

from websockets.sync.client import connect

import pytest

from ..conftest import start_server, stop_server


@pytest.fixture(scope="module")
def demo_server():
    running = start_server()
    yield running
    stop_server(running)


def test_default_demo_shows_a_left_and_a_right_hand_of_each_kind_moving(demo_server):
    robots = demo_server.get("/api/scenes/default/robots")
    assert sorted(r["type"] for r in robots) == sorted(["EdgedHand", "RoundHand", "AnthroHand"] * 2)
    first = demo_server.get(f"/api/scenes/default/robots/{robots[2]['id']}")["motors"]
    time.sleep(0.3)
    later = demo_server.get(f"/api/scenes/default/robots/{robots[2]['id']}")["motors"]
    assert [m["angle"] for m in first] != [m["angle"] for m in later]


@pytest.fixture
def diggers(demo_server):
    with connect(f"{demo_server.ws}/ws?scene=diggers&role=viewer") as ws:
        ws.recv(timeout=10)
        yield ws


def test_demo_diggers_are_where_the_manual_puts_them_and_move(demo_server, diggers):
    robots = demo_server.get("/api/scenes/diggers/robots")
    assert [r["position"] for r in robots] == [[0, 0, 1], [0, 0, 0], [0, 0, -1]]
    assert all(r["motors"] == 3 for r in robots)
    first = [demo_server.get(f"/api/scenes/diggers/robots/{r['id']}")["motors"] for r in robots]
    time.sleep(0.2)
    later = [demo_server.get(f"/api/scenes/diggers/robots/{r['id']}")["motors"] for r in robots]
    for before, after in zip(first, later):
        assert [m["angle"] for m in before] != [m["angle"] for m in after]
        assert [(m["min"], m["max"]) for m in after] == [(-0.7, 0.7), (-1.6, 0), (-1.6, 0)]
        assert all(m["min"] <= m["angle"] <= m["max"] for m in after)
