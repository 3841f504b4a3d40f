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
# How long a test waits for what the product will do (a frame, a file saved, a process
# gone): a hang guard, never a measure. A wait ends as soon as its condition holds, so a
# long guard costs nothing on a fast machine and keeps a slow or loaded one (a single core
# running the whole suite) from failing a test that would have passed.
WAIT_SECONDS = 60.0
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
        with urllib.request.urlopen(request, timeout=WAIT_SECONDS) as response:
            return json.loads(response.read())

    def post(self, path: str) -> tuple[int, Any]:
        """POST to a REST path with an empty body; the status and the decoded JSON body
        (raises HTTPError for 4xx/5xx)."""
        headers = {"Authorization": f"Bearer {self.token}"} if self.token else {}
        request = urllib.request.Request(self.http + path, data=b"", method="POST",
                                         headers=headers)
        with urllib.request.urlopen(request, timeout=WAIT_SECONDS) as response:
            return response.status, json.loads(response.read())

    def figures(self, scene: str) -> dict[str, Any]:
        """The scene's entry in /api/metrics once its process has answered (one that has not
        within the server's second, on a loaded machine, has only the server's own figures:
        bench-quick failed on a KeyError in the suite). The tests' and the bench's."""
        deadline = time.monotonic() + WAIT_SECONDS
        while "ticks" not in (found := self.get("/api/metrics")["scenes"].get(scene) or {}):
            assert time.monotonic() < deadline, f"scene {scene} gave no figures: {found}"
            time.sleep(0.05)
        return found

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


def eventually(check: Any, timeout: float = WAIT_SECONDS) -> None:
    """Wait until ``check()`` is true: frames, closes and clean-ups happen on the server's
    schedule, not the test's. Asked every 10 ms at first, then less often, down to every
    50 ms: a check through REST costs the server and the test about 7 ms of CPU, so a
    fixed 10 ms kept most of a core busy for as long as a test waited."""
    deadline, pause = time.monotonic() + timeout, 0.01
    while not check():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(pause)
        pause = min(1.5 * pause, 0.05)


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
    deadline = time.monotonic() + WAIT_SECONDS
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
    server.process.wait(timeout=WAIT_SECONDS)


def stop_server(server: RunningServer) -> None:
    server.process.send_signal(signal.SIGINT)
    try:
        server.process.wait(timeout=WAIT_SECONDS)
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



def run_program(module: str, *args: str) -> Any:
    """What ``python -m module args`` printed (JSON); it must end well."""
    run = subprocess.run([sys.executable, "-m", module, *args], cwd=ROOT, capture_output=True,
                         timeout=600)
    assert run.returncode == 0, run.stderr[-2000:].decode(errors="replace")
    return json.loads(run.stdout)


def descendants(pid: int) -> list[int]:
    """Every process below ``pid`` (Linux's /proc children lists)."""
    found, todo = [], [pid]
    while todo:
        for task in Path(f"/proc/{todo.pop()}/task").glob("*"):
            try:
                children = [int(c) for c in (task / "children").read_text().split()]
            except OSError:
                continue
            found += children
            todo += children
    return found


def alive(pid: int) -> bool:
    """Whether process ``pid`` runs (not gone, not a zombie)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().split(") ")[1][0] != "Z"
    except OSError:
        return False


def pytest_xdist_auto_num_workers(config: pytest.Config) -> int:
    """``-n auto`` (the suite's default): two workers for each core this process may use.
    Much of a test waits on a server: with three on two cores the cores stood idle at
    times, four keep them busy (3 % idle over a whole run); pinned to one core, two."""
    return 2 * len(os.sched_getaffinity(0))


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Files marked ``long`` go to the workers first (a stable sort keeps every other order):
    dealt out last, one long file kept a worker busy after the others had finished."""
    items.sort(key=lambda item: item.get_closest_marker("long") is None)
