"""The JavaScript client in Node: its own tests (node:test, against the real server), and
the manual's Steps 2-5 run unchanged but for the import and connect()."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from tests.conftest import WAIT_SECONDS

CLIENT = Path(__file__).resolve().parents[3] / "clients" / "js"


def test_the_javascript_client_tests_pass(server):
    result = subprocess.run(["node", "--test", "test/"], cwd=CLIENT, capture_output=True,
                            text=True, timeout=300, env={**os.environ, "VP_URL": server.ws})
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert "# fail 0" in result.stdout and "# skipped 0" in result.stdout
    assert "# pass 0" not in result.stdout


def _angles(server, scene: str) -> list[float]:
    return [n["angle"] for n in server.nodes(scene) if n["type"] == "MotorZ"]


@pytest.mark.parametrize("step, robots, moving", [(2, 1, False), (3, 1, True), (4, 1, True),
                                                  (5, 3, True)])
def test_the_manual_steps_run_in_node(server, scene_name, step, robots, moving):
    env = {**os.environ, "VP_URL": server.ws, "VP_SCENE": scene_name}
    node = subprocess.Popen(["node", f"examples/step{step}.mjs"], cwd=CLIENT, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + WAIT_SECONDS
        while len(server.robots(scene_name)) < robots and time.monotonic() < deadline:
            time.sleep(0.1)
        assert len(server.robots(scene_name)) == robots
        first = _angles(server, scene_name)
        # moving: the animation starts after the robots are made, later on a busy machine
        deadline = time.monotonic() + (WAIT_SECONDS if moving else 0.5)
        while _angles(server, scene_name) == first and time.monotonic() < deadline:
            time.sleep(0.1)
        assert (_angles(server, scene_name) != first) == moving
        node.send_signal(signal.SIGINT)
        out, err = node.communicate(timeout=WAIT_SECONDS)
    finally:
        node.kill()
    assert node.returncode == 0, err
    assert "Virtual Prosthetics 1.0" in out
    # found: only the banner; it never said which scene it joined or where to watch
    assert f"scene {scene_name} on {server.ws}; watch at {server.http}/view?scene={scene_name}" in out
    deadline = time.monotonic() + WAIT_SECONDS
    while server.robots(scene_name) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert server.robots(scene_name) == []
