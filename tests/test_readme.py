"""The README's walkthrough as a newcomer runs it: every code block, extracted from
README.md, run literally against a server with its demo on a free port, so the README
cannot drift from the product. The only changes: the address (``127.0.0.1:8000`` becomes
the test server's) and the recording's ``sleep 10`` a second. A block is run here or
listed in ``NOT_RUN`` with the reason, so a new block cannot go unchecked."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path
from typing import Iterator

import pytest

from tests.conftest import (ROOT, WAIT_SECONDS, RunningServer, eventually, free_port, start_server,
                            stop_server)

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first

BLOCK = re.compile(r"^```(\w*)\n(.*?)^```", re.S | re.M)
README_ADDRESS = "127.0.0.1:8000"

# a block's first line (its start) -> why it is not run here
NOT_RUN = {
    "make run": "the two commands themselves: CI runs `make test` on a clean clone",
    ".venv/bin/python -m virtual_prosthetics.tasks grasp --url": "minutes of trials; "
    "tests/clients/python/tasks run every task and the command line (test_main)",
    "make test-container": "needs a container engine; tests/test_container_files.py checks "
    "the files",
    "nats-server -c": "a cluster over several machines; tests/server/cluster start one",
    "server/ ": "the layout, not a command",
}


# the blocks run here, by their first lines
START_EXPORT = "curl -s http://127.0.0.1:8000/api/scenes/default/export > lab.json"
START_REPORT = "curl -s http://127.0.0.1:8000/api/scenes/default/robots/demo.EdgedHand-left"
START_RECORDING = "id=$(curl -s -X POST http://127.0.0.1:8000/api/scenes/default/recordings"
START_URDF = "curl -sfOJ http://127.0.0.1:8000/api/scenes/default/robots/demo.RoundHand-left/urdf"
START_UPLOAD = "curl -s --data-binary @hand.zip"
START_GYM = "import gymnasium as gym"
START_DIGGER = "import math\nimport virtual_prosthetics as vp"
START_PAD = "class Pad(vp.Box):"
START_PAGE = '<script type="module">'


def blocks() -> list[tuple[str, str]]:
    """(language, text) of every fenced block of README.md, in order."""
    return [(match[1], match[2]) for match in BLOCK.finditer((ROOT / "README.md").read_text())]


def block(start: str) -> str:
    """The one block that starts with ``start``."""
    [found] = [text for _, text in blocks() if text.startswith(start)]
    return found


def _skipped(text: str) -> bool:
    return any(text.startswith(start) for start in NOT_RUN)


@pytest.fixture(scope="module")
def demo() -> Iterator[RunningServer]:
    running = start_server()  # with the demo, as `make run`
    yield running
    stop_server(running)


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Where the newcomer stands: a folder with the project's `.venv` (as `make` made it)."""
    made = tmp_path_factory.mktemp("newcomer")
    (made / ".venv").symlink_to(ROOT / ".venv")
    return made


def literal(text: str, server: RunningServer) -> str:
    return text.replace(README_ADDRESS, f"127.0.0.1:{server.port}")


def run_shell(text: str, server: RunningServer, folder: Path) -> str:
    done = subprocess.run(["bash", "-e", "-c", literal(text, server)], cwd=folder, text=True,
                          capture_output=True, timeout=WAIT_SECONDS * 2)
    assert done.returncode == 0, done.stderr + done.stdout
    return done.stdout


def run_python(text: str, server: RunningServer, folder: Path, timeout: float = WAIT_SECONDS
               ) -> str:
    done = subprocess.run([sys.executable, "-c", literal(text, server)], cwd=folder, text=True,
                          capture_output=True, timeout=timeout)
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout


def test_every_block_is_run_here_or_says_why_not():
    run_here = [START_EXPORT, START_REPORT, START_RECORDING, START_URDF, START_UPLOAD,
                START_GYM, START_DIGGER, START_PAD, START_PAGE]
    for language, text in blocks():
        assert _skipped(text) or any(text.startswith(start) for start in run_here), (
            f"a README block nobody runs ({language}): {text[:80]!r}")
    for start in run_here:
        block(start)  # each is still there, once


def test_the_shell_walkthrough_runs_as_written(demo, folder):
    """Export and import a scene, read a robot, record, export a hand and load it in
    PyBullet, upload it again: each block in turn, in one folder."""
    imported = json.loads(run_shell(block(START_EXPORT), demo, folder))
    assert imported["scene"] == "lab-copy" and imported["objects"] > 6
    report = json.loads(run_shell(block(START_REPORT), demo, folder))
    assert report["id"] == "demo.EdgedHand-left" and report["parts"]
    run_shell(block(START_RECORDING).replace("sleep 10;", "sleep 1;"), demo, folder)
    assert (folder / "demo.mcap").read_bytes()[:8] == b"\x89MCAP0\r\n"
    loaded = run_shell(block(START_URDF), demo, folder)
    assert loaded.strip().splitlines()[-1] == "0"  # PyBullet's first body
    assert (folder / "hand.glb").read_bytes()[:4] == b"glTF"
    # the upload block takes the reader's own hand.zip: here, the hand just exported
    shutil.copy(folder / "demo.RoundHand-left.zip", folder / "hand.zip")
    assert zipfile.is_zipfile(folder / "hand.zip")
    uploaded = json.loads(run_shell(block(START_UPLOAD), demo, folder))
    assert uploaded["motors"] and uploaded["id"] in {r["id"] for r in demo.robots("default")}


def test_the_python_examples_run_as_written(demo, folder):
    """The Diggers run their 10 s (in the background meanwhile), the pad prints its
    contact (with the Diggers' own connect line before it), the Gymnasium example steps."""
    before = {robot["id"] for robot in demo.robots("default")}
    digger = subprocess.Popen([sys.executable, "-c", literal(block(START_DIGGER), demo)],
                              cwd=folder, text=True, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE)
    try:
        eventually(lambda: _new_diggers(demo, before))
        [made] = _new_diggers(demo, before)
        angles = _angles(demo, made)
        eventually(lambda: _angles(demo, made) != angles)  # it digs
        connect = block(START_DIGGER).split("\nclass ")[0]  # imports and vp.connect
        printed = run_python(f"{connect}\n{block(START_PAD)}", demo, folder)
        assert "touched ground" in printed
        printed = run_python(block(START_GYM), demo, folder)
        assert f"http://127.0.0.1:{demo.port}/view?scene=" in printed  # where to watch
        out, err = digger.communicate(timeout=WAIT_SECONDS)
    finally:
        digger.kill()
    assert digger.returncode == 0, err[-3000:]  # vp.run(10) ended it


def _new_diggers(server: RunningServer, before: set[str]) -> list[str]:
    return [robot["id"] for robot in server.robots("default")
            if robot["id"] not in before and len(robot["motors"]) == 3]


def _angles(server: RunningServer, robot: str) -> list[float]:
    return _angles_in(server, "default", robot)


def _angles_in(server: RunningServer, scene: str, robot: str) -> list[float]:
    nodes = {node["id"]: node for node in server.nodes(scene)}
    return [nodes[motor]["angle"] for motor in nodes[robot]["motors"]]


def test_the_page_example_runs_as_written(demo, folder):
    """The 1.0 page with its import line changed, saved in the reader's own folder and
    served there (a loopback origin the server lets in), draws its robot in a scene."""
    from tests.web.conftest import CHROMIUM, FLAGS  # noqa: PLC0415 (only this test needs it)
    from playwright.sync_api import sync_playwright  # noqa: PLC0415
    (folder / "page.html").write_text(literal(block(START_PAGE), demo))
    port = free_port()
    served = subprocess.Popen([sys.executable, "-m", "http.server", str(port), "--bind",
                               "127.0.0.1"], cwd=folder, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    try:
        with sync_playwright() as playwright:
            chromium = playwright.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
            page = chromium.new_page()
            page.set_default_timeout(WAIT_SECONDS * 1000)
            _goto_when_served(page, f"http://127.0.0.1:{port}/page.html")
            page.wait_for_function("() => window.VP && VP.objects.size >= 4")
            link = page.eval_on_selector("#status a", "(a) => a.href")
            scene = link.split("scene=")[1]
            [robot] = demo.robots(scene)
            angles = _angles_in(demo, scene, robot["id"])
            eventually(lambda: _angles_in(demo, scene, robot["id"]) != angles)  # setAnimation
            chromium.close()
    finally:
        served.kill()


def _goto_when_served(page, url: str) -> None:
    for _ in range(50):
        try:
            page.goto(url)
            return
        except Exception:  # noqa: BLE001 (the folder's server is still starting)
            page.wait_for_timeout(100)
    page.goto(url)
