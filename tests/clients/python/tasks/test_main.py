"""The tasks CLI when something is wrong: every mistake and failure is one line saying what
to do (exit 1; argparse's own: 2), never a traceback."""

from __future__ import annotations

import subprocess
import sys
from typing import Iterator

import pytest

import virtual_prosthetics as vp
from virtual_prosthetics.errors import ConnectionLost
from virtual_prosthetics.tasks.__main__ import _fix
from tests.conftest import ROOT, RunningServer, free_port, start_server, stop_server


@pytest.fixture(scope="module")
def guarded() -> Iterator[RunningServer]:
    running = start_server("--no-demo", "--token", "right")
    yield running
    stop_server(running)


def _run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "virtual_prosthetics.tasks", "grasp",
                           "--trials", "1", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=120)


@pytest.mark.parametrize("case, named", [
    ("no server", "start a server (make run) or give its address with --url"),
    ("no token", "--token T"),
    ("wrong token", "--token T"),
    ("http address", "is not a WebSocket address: ws://HOST:PORT"),
    ("no address", "is not a WebSocket address"),
    ("bad scene", "scene names are 1-64 letters"),
])
def test_a_mistake_is_one_line_naming_the_fix(guarded, case, named):
    options = {"no server": ["--url", f"ws://127.0.0.1:{free_port()}"],
               "no token": ["--url", guarded.ws],
               "wrong token": ["--url", guarded.ws, "--token", "wrong"],
               "http address": ["--url", guarded.http],
               "no address": ["--url", "lab"],
               "bad scene": ["--url", guarded.ws, "--token", "right", "--scene", "my lab"]}[case]
    run = _run(*options)
    assert run.returncode == 1 and run.stdout == ""
    assert run.stderr.count("\n") == 1 and run.stderr.startswith("error: "), run.stderr
    assert named in run.stderr and "right" not in run.stderr  # and never the token


def test_a_controller_that_cannot_be_imported_is_an_argument_error():
    run = _run("--controller", "no_such_module:make")
    assert run.returncode == 2 and "Traceback" not in run.stderr
    assert "argument --controller: cannot import 'no_such_module'" in run.stderr.splitlines()[-1]


def test_a_connection_lost_mid_run_says_the_run_did_not_finish():
    said = _fix(ConnectionLost("connection closed: no close frame received or sent"), "ws://x")
    assert said.endswith("the run did not finish") and "no close frame" in said


def test_a_scene_another_run_steps_is_reported_before_anything_changes(guarded, scene_name):
    holder = vp.connect(guarded.ws, scene=scene_name, token="right")
    try:
        holder.pause()
        run = _run("--url", guarded.ws, "--token", "right", "--scene", scene_name)
        assert run.returncode == 1 and run.stdout == ""
        assert run.stderr.count("\n") == 1 and "--scene NAME" in run.stderr, run.stderr
        assert f"held by {holder.client_id}" in run.stderr, run.stderr
        holder.sync()
        assert holder.get_physics()["mode"] == "kinematic"  # the refused run changed nothing
    finally:
        holder.close()
