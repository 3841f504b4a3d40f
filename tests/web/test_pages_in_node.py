"""1.0 example pages run as Node scripts (clients/js/examples/page.mjs): the page's module
script, its import line made Node's (and connect() added, as the manual's steps in Node
have it). Their reads are 1.0's,
their robots appear on the server and move, and a browser watching the scene sees them."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from tests.conftest import WAIT_SECONDS
from .conftest import open_viewer, wait_until
from .test_client_pages import READS, _moves, _wait_for_robots, check_reads_page_robots

RUNNER = Path(__file__).resolve().parents[2] / "clients" / "js" / "examples" / "page.mjs"


@pytest.mark.parametrize("example, robots", [("robot-reads", 2), ("two-hands", 2)])
def test_an_example_page_runs_in_node(browser, pages, server, scene_name, example, robots):
    env = {**os.environ, "VP_URL": server.ws, "VP_SCENE": scene_name}
    node = subprocess.Popen(["node", str(RUNNER), example], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        _wait_for_robots(server, scene_name, robots)
        if example == "robot-reads":
            check_reads_page_robots(server, scene_name)
        assert _moves(server, scene_name, True)
        ids = [n["id"] for n in server.nodes(scene_name)]
        viewer = open_viewer(browser, pages, server, f"scene={scene_name}")
        wait_until(viewer, "(ids) => ids.every((id) => VP.objects.has(id))", ids)
        node.send_signal(signal.SIGINT)
        out, err = node.communicate(timeout=WAIT_SECONDS)
    finally:
        node.kill()
    assert node.returncode == 0, err
    if example == "robot-reads":
        assert [line for line in out.splitlines() if line in READS] == READS
        # one warning per call that left coordinates out, naming what it kept
        assert err.count("left out") == 2 and "setRotation left out z" in err, err
    deadline = time.monotonic() + WAIT_SECONDS
    while server.robots(scene_name) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert server.robots(scene_name) == []
