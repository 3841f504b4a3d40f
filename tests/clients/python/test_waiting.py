"""Clients wait as long as the user says: ``timeout=`` (Python), ``connect({timeout})``
(JavaScript), the tasks CLI's ``--timeout`` and ``VP_TIMEOUT``; a timeout's message names
how to wait longer.

The server under load is a scene process that gets no CPU for 11 s: it is stopped
(SIGSTOP), as a process starved by a busy machine looks from outside, and started again.
The 1.0 clients' old fixed 10 s would have given up on it.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any, Callable

import pytest

import virtual_prosthetics as vp
from virtual_prosthetics.waiting import DEFAULT_SECONDS, wait_seconds
from tests.conftest import ROOT, RunningServer

STOPPED_SECONDS = 11.0  # more than the clients' old fixed 10 s
JS_CLIENT = ROOT / "clients" / "js"
NODE_CONNECT = """
import * as vp from './virtual-prosthetics.js';
import { DEFAULT_SECONDS } from './waiting.js';
const [url, scene, timeout] = process.argv.slice(1);
const seconds = timeout === 'env' ? undefined : Number(timeout);
try {
    const session = await vp.connect({ url, scene, timeout: seconds });
    console.log(JSON.stringify({ connected: session.clientId, byDefault: DEFAULT_SECONDS }));
    new vp.Box();
    await vp.sync();
    console.log(JSON.stringify({ synced: true }));
    vp.close();
} catch (error) {
    console.log(JSON.stringify({ error: error.name, message: error.message }));
    process.exit(0);
}
"""


class StoppedScene:
    """A scene whose process is stopped from :meth:`stop` until ``seconds`` later."""

    def __init__(self, server: RunningServer, scene: str, seconds: float) -> None:
        self.pid = server.get("/api/metrics")["scenes"][scene]["pid"]
        self.seconds = seconds
        self.resumed = threading.Event()

    def stop(self) -> None:
        os.kill(self.pid, signal.SIGSTOP)
        timer = threading.Timer(self.seconds, self.resume)
        timer.daemon = True
        timer.start()

    def resume(self) -> None:
        os.kill(self.pid, signal.SIGCONT)
        self.resumed.set()


def _connect_python(server: RunningServer, scene: str, timeout: float | None) -> dict[str, Any]:
    started = time.monotonic()
    try:
        session = vp.Session(server.ws, scene, timeout=timeout)
    except vp.Timeout as error:
        return {"error": error, "after": time.monotonic() - started}
    session.close()
    return {"connected": True, "after": time.monotonic() - started}


def _run_node(server: RunningServer, scene: str, timeout: str,
              env: dict[str, str] | None = None) -> list[dict[str, Any]]:
    run = subprocess.run(["node", "--input-type=module", "-e", NODE_CONNECT, server.ws, scene,
                          timeout], cwd=JS_CLIENT, capture_output=True, text=True, timeout=120,
                         env={**os.environ, **(env or {})})
    assert run.returncode == 0, run.stderr
    return [json.loads(line) for line in run.stdout.splitlines() if line.startswith("{")]


def _run_tasks_cli(server: RunningServer, scene: str, *options: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "virtual_prosthetics.tasks", "grasp",
                           "--url", server.ws, "--scene", scene, "--trials", "1", *options],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)


def test_a_stopped_scene_is_waited_for_as_long_as_each_client_says(server, scene_name):
    """One window of 11 s without a scene process: the short waits end in a Timeout that
    names how to wait longer, the long (and default) ones connect once it runs again."""
    keeper = vp.Session(server.ws, scene_name)  # the scene exists meanwhile
    stopped = StoppedScene(server, scene_name, STOPPED_SECONDS)
    short_reader = vp.Session(server.ws, scene_name, timeout=2)
    calls: dict[str, Callable[[], Any]] = {
        "python short": lambda: _connect_python(server, scene_name, 2),
        "python long": lambda: _connect_python(server, scene_name, 60),
        "python default": lambda: _connect_python(server, scene_name, None),
        "node short": lambda: _run_node(server, scene_name, "2"),
        "node long": lambda: _run_node(server, scene_name, "60"),
        "node from VP_TIMEOUT": lambda: _run_node(server, scene_name, "env", {"VP_TIMEOUT": "3"}),
        "cli short": lambda: _run_tasks_cli(server, scene_name, "--timeout", "2"),
    }
    try:
        stopped.stop()
        with ThreadPoolExecutor(len(calls) + 1) as pool:
            futures = {name: pool.submit(call) for name, call in calls.items()}
            futures["read"] = pool.submit(_write_then_read, short_reader)
            found = {name: future.result(timeout=120) for name, future in futures.items()}
    finally:
        stopped.resume()
        short_reader.close()
        keeper.close()

    for name in ("python short", "python default", "python long"):
        assert ("error" in found[name]) == (name == "python short"), (name, found[name])
    short = found["python short"]["error"]
    assert short.seconds == 2 and f"scene '{scene_name}'" in str(short)
    assert "timeout=S" in str(short) and "VP_TIMEOUT=S" in str(short)
    assert found["python long"]["after"] > 10 < found["python default"]["after"]

    assert found["read"].seconds == 2 and "no answer to" in str(found["read"])

    node_short, = found["node short"]
    assert node_short["error"] == "Timeout"
    assert "within 2 s" in node_short["message"] and "connect({timeout: S})" in node_short["message"]
    assert "VP_TIMEOUT=S" in node_short["message"]
    assert found["node from VP_TIMEOUT"][0]["error"] == "Timeout"
    assert "within 3 s" in found["node from VP_TIMEOUT"][0]["message"]
    connected, synced = found["node long"]
    assert connected["connected"] and synced == {"synced": True}
    assert connected["byDefault"] == DEFAULT_SECONDS  # the two clients' defaults agree

    cli = found["cli short"]
    assert cli.returncode == 1 and "Traceback" not in cli.stderr
    assert cli.stderr.strip().count("\n") == 0, cli.stderr  # one line
    assert "within 2 s" in cli.stderr and "--timeout S" in cli.stderr


def _write_then_read(session: vp.Session) -> vp.Timeout:
    """A write sent while the scene is stopped, then a read that waits for it."""
    with pytest.raises(vp.Timeout) as caught:
        vp.Box(scene=session)
        session.sync()
    return caught.value


def test_the_tasks_cli_takes_a_timeout_and_refuses_a_wrong_one():
    run = subprocess.run([sys.executable, "-m", "virtual_prosthetics.tasks", "grasp",
                          "--timeout", "-1"], cwd=ROOT, capture_output=True, text=True,
                         timeout=60)
    assert run.returncode == 2 and "--timeout" in run.stderr
    assert "positive number of seconds" in run.stderr


@pytest.mark.parametrize("given, environment, expected", [
    (None, None, DEFAULT_SECONDS), (None, "", DEFAULT_SECONDS), (None, "2.5", 2.5),
    (7, "2.5", 7.0), (float("inf"), None, float("inf")),
])
def test_the_wait_is_the_callers_else_the_environments_else_the_default(
        monkeypatch, given, environment, expected):
    if environment is None:
        monkeypatch.delenv("VP_TIMEOUT", raising=False)
    else:
        monkeypatch.setenv("VP_TIMEOUT", environment)
    assert wait_seconds(given) == expected


@pytest.mark.parametrize("given, environment, named", [
    (0, None, "timeout"), (-3, None, "timeout"), (float("nan"), None, "timeout"),
    ("10", None, "timeout"), (True, None, "timeout"), (None, "soon", "VP_TIMEOUT"),
    (None, "-1", "VP_TIMEOUT"),
])
def test_a_wait_that_is_not_a_positive_number_is_refused_naming_its_source(
        monkeypatch, given, environment, named):
    monkeypatch.delenv("VP_TIMEOUT", raising=False)
    if environment is not None:
        monkeypatch.setenv("VP_TIMEOUT", environment)
    with pytest.raises(ValueError, match=named):
        wait_seconds(given)
