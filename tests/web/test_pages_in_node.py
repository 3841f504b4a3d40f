"""1.0 example pages run as Node scripts: the page's module script, its import line made
Node's (and connect() added, as the manual's steps in Node have it). Their reads are 1.0's,
their robots appear on the server and move, and a browser watching the scene sees them."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import time
from pathlib import Path

import pytest

from tests.conftest import WAIT_SECONDS
from .conftest import open_viewer, wait_until
from .test_client_pages import EXAMPLES, READS, _moves, _wait_for_robots, check_reads_page_robots

CLIENT = Path(__file__).resolve().parents[2] / "clients" / "js" / "virtual-prosthetics.js"
PAGE_IMPORT = 'import * as Prosthetic from "/client/virtual-prosthetics.js";'


def as_node_script(page: str) -> str:
    """The page's module script with only its import line changed for Node."""
    script = re.search(r'<script type="module">(.*?)</script>', page, re.S).group(1)
    assert script.count(PAGE_IMPORT) == 1
    return script.replace(PAGE_IMPORT, f'import * as Prosthetic from "{CLIENT.as_uri()}";\n'
                          "await Prosthetic.connect({ url: process.env.VP_URL, "
                          "scene: process.env.VP_SCENE });")


@pytest.mark.parametrize("example, robots", [("robot-reads", 2), ("edged-hand", 2)])
def test_an_example_page_runs_in_node(browser, pages, server, scene_name, tmp_path,
                                      example, robots):
    script = tmp_path / f"{example}.mjs"
    script.write_text(as_node_script((EXAMPLES / f"{example}.html").read_text()))
    env = {**os.environ, "VP_URL": server.ws, "VP_SCENE": scene_name}
    node = subprocess.Popen(["node", str(script)], env=env, stdout=subprocess.PIPE,
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
