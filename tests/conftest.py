"""Shared fixtures: a real server on a free loopback port, started once per test session."""

from __future__ import annotations

import contextlib
import json
import os
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from dataclasses import dataclass
from itertools import count
from pathlib import Path
from typing import Any, Iterator

import pytest

ROOT = Path(__file__).resolve().parents[1]
VP_SERVER = Path(sys.executable).with_name("vp-server")
_scene_numbers = count(1)


@dataclass
class RunningServer:
    """A vp-server process and how to reach it."""

    process: subprocess.Popen[bytes]
    port: int
    token: str | None = None  # sent with every REST read (a server that asks for one)

    @property
    def http(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    @property
    def ws(self) -> str:
        return f"ws://127.0.0.1:{self.port}"

    def get(self, path: str) -> Any:
        """GET a REST path; the decoded JSON body (raises HTTPError for 4xx/5xx)."""
        headers = {"Authorization": f"Bearer {self.token}"} if self.token else {}
        request = urllib.request.Request(self.http + path, headers=headers)
        with urllib.request.urlopen(request, timeout=10) as response:
            return json.loads(response.read())

    def nodes(self, scene: str) -> list[dict[str, Any]]:
        """The scene's nodes as its snapshot lists them; none while the scene is not there."""
        try:
            return self.get(f"/api/scenes/{scene}/snapshot")["nodes"]
        except urllib.error.HTTPError as error:
            if error.code == 404:
                return []
            raise

    def robots(self, scene: str) -> list[dict[str, Any]]:
        """The scene's robots and hands (the nodes that list motors)."""
        return [n for n in self.nodes(scene) if "motors" in n]


def eventually(check: Any, timeout: float = 5.0) -> None:
    """Wait until ``check()`` is true: frames, closes and clean-ups happen on the server's
    schedule, not the test's."""
    deadline = time.monotonic() + timeout
    while not check():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.01)


@contextlib.contextmanager
def unwritable(folder: Path) -> Iterator[None]:
    """No file can be made, renamed or removed in ``folder`` meanwhile (files open in it
    can still be written): ``chattr +i`` as root, whom permissions do not stop, else a
    read-only mode."""
    root = os.geteuid() == 0
    if root:
        subprocess.run(["chattr", "+i", str(folder)], check=True)
    else:
        folder.chmod(0o555)
    try:
        yield
    finally:
        if root:
            subprocess.run(["chattr", "-i", str(folder)], check=True)
        else:
            folder.chmod(0o755)


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def start_server(*args: str, port: int | None = None, log: Path | None = None) -> RunningServer:
    """Start vp-server (on a free port unless told) and wait until /api/health answers;
    its output goes to ``log`` when given. It leads a process group of its own (with its
    scenes' processes: :func:`crash_server`)."""
    port = port or free_port()
    output = open(log, "wb") if log is not None else None  # noqa: SIM115 (the process keeps it)
    process = subprocess.Popen([str(VP_SERVER), "--port", str(port), "--log-level", "warning",
                                *args], cwd=ROOT, stdout=output, stderr=output,
                               start_new_session=True)
    server = RunningServer(process, port)
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        if process.poll() is not None:
            raise RuntimeError(f"vp-server exited with {process.returncode}")
        try:
            server.get("/api/health")
            return server
        except OSError:
            time.sleep(0.1)
    process.kill()
    raise RuntimeError("vp-server did not answer /api/health within 30 s")


def crash_server(server: RunningServer) -> None:
    """``kill -9`` the server and every process of its scenes at once: nothing gets to
    save anything."""
    os.killpg(server.process.pid, signal.SIGKILL)
    server.process.wait(timeout=10)


def stop_server(server: RunningServer) -> None:
    server.process.send_signal(signal.SIGINT)
    try:
        server.process.wait(timeout=10)
    except subprocess.TimeoutExpired:
        server.process.kill()


@pytest.fixture(scope="session")
def server() -> Iterator[RunningServer]:
    """A server with an empty default scene (no demo), shared by the whole session; what a
    client made goes 1 s after it leaves (10 s by default)."""
    running = start_server("--no-demo", "--limit", "leaveGraceSeconds=1")
    yield running
    stop_server(running)


@pytest.fixture
def scene_name() -> str:
    """A scene name no other test uses, so tests on the shared server never meet."""
    return f"t{os.getpid()}x{next(_scene_numbers)}"


# --- long programs that run beside the suite -----------------------------------------------
# A fuzzer of 10 000 cases is a minute of one core. Such programs start at nice 19 as soon as
# the tests that read them are collected, use what the rest of the suite leaves idle, and
# the test reads what the program printed (waiting for it if it is not done yet).

_BESIDE: dict[tuple[str, ...], subprocess.Popen[bytes]] = {}


def pytest_configure(config: Any) -> None:
    config.addinivalue_line("markers", "beside(*argv): a program (python -m ...) whose JSON "
                                       "output the test reads; started when collected")


def pytest_collection_finish(session: Any) -> None:
    for item in session.items:
        marker = item.get_closest_marker("beside")
        if marker is not None and marker.args not in _BESIDE:
            _BESIDE[marker.args] = subprocess.Popen(
                ["nice", "-n", "19", sys.executable, "-m", *marker.args], cwd=ROOT,
                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, start_new_session=True)


def pytest_sessionfinish(session: Any) -> None:
    for process in _BESIDE.values():
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)


@pytest.fixture
def beside(request: Any) -> Any:
    """What the test's ``beside`` program printed (JSON), once it has ended."""
    marker = request.node.get_closest_marker("beside")
    process = _BESIDE.get(marker.args) or _BESIDE.setdefault(marker.args, subprocess.Popen(
        [sys.executable, "-m", *marker.args], cwd=ROOT, stdout=subprocess.PIPE))
    output, _ = process.communicate(timeout=600)
    assert process.returncode == 0, f"{' '.join(marker.args)} ended with {process.returncode}"
    return json.loads(output)
