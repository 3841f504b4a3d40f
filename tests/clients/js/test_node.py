"""The JavaScript client in Node: its own tests (node:test, against the real server), and
the example pages (the manual's Steps 2-5 among them) run in Node unchanged but for the
import line."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from tests.conftest import WAIT_SECONDS

CLIENT = Path(__file__).resolve().parents[3] / "clients" / "js"


# one test a file (each about a second alone): run as one, the files took 64-77 s beside
# the suite's others on a 2-core machine, near the per-test hang guard on a slower one
TEST_FILES = sorted(path.name for path in (CLIENT / "test").glob("*.test.js"))


@pytest.mark.parametrize("test_file", TEST_FILES)
def test_the_javascript_client_tests_pass(server, test_file):
    result = subprocess.run(["node", "--test", f"test/{test_file}"], cwd=CLIENT,
                            capture_output=True, text=True, timeout=300,
                            env={**os.environ, "VP_URL": server.ws})
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert "# fail 0" in result.stdout and "# skipped 0" in result.stdout
    assert "# pass 0" not in result.stdout


def test_every_javascript_test_file_is_run():
    # a file named otherwise (``*.spec.js``, say) would be left out of the parametrization
    scripts = {path.name for path in (CLIENT / "test").glob("*.js")}
    helpers = {name for name in scripts if not name.endswith(".test.js")}
    assert len(TEST_FILES) >= 19 and all(not _has_tests(CLIENT / "test" / name) for name in helpers)


def _has_tests(path: Path) -> bool:
    return "from 'node:test'" in path.read_text() or 'from "node:test"' in path.read_text()


def _angles(server, scene: str) -> list[float]:
    return [n["angle"] for n in server.nodes(scene) if n["type"].startswith("Motor")]


@pytest.mark.parametrize("page, robots, moving", [
    ("simple-robot-2", 1, False), ("simple-robot-3", 1, True), ("simple-robot-4", 1, True),
    ("digger", 3, True), ("two-hands?hand=AnthroHand", 2, True)])
def test_the_example_pages_run_in_node(server, scene_name, page, robots, moving):
    env = {**os.environ, "VP_URL": server.ws}
    node = subprocess.Popen(["node", "examples/page.mjs", page, scene_name], cwd=CLIENT, env=env,
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


def test_a_page_that_is_not_there_is_named():
    result = subprocess.run(["node", "examples/page.mjs", "no-such-page"], cwd=CLIENT,
                            capture_output=True, text=True, timeout=WAIT_SECONDS)
    assert result.returncode != 0 and "no-such-page.html" in result.stderr
    result = subprocess.run(["node", "examples/page.mjs", "../../etc/passwd"], cwd=CLIENT,
                            capture_output=True, text=True, timeout=WAIT_SECONDS)
    assert result.returncode == 2 and "usage" in result.stderr
