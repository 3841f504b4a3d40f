"""Measures of a running server from outside: its tick while a client drives it, latency
from one client to another, many viewers, and two busy scenes side by side.

Every client runs in a process of its own at a lower priority (:mod:`bench.drive`,
:mod:`bench.viewers`): on this 2-core machine they share the cores with the server, as
they would not on the clients' machines.
"""

from __future__ import annotations

import json
import math
import random
import subprocess
import sys
import threading
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Callable, Iterator

from websockets.sync.client import connect

from tests.conftest import RunningServer, start_server, stop_server

from .drive import build, drain
from .processes import descendants
from .stats import figure
from .viewers import run_viewers, sleep_until

ROOT = Path(__file__).resolve().parents[1]
LIMITS = ("--limit", "bytesPerSecond=1000000000",
          "--limit", "connectionsPerAddress=2000", "--limit", "connections=2000")
NICE = ("nice", "-n", "10")
# how long a change may take to show before the measure gives up: a stuck server, not a slow
# one (the suite runs bench-quick on loaded machines)
STUCK_SECONDS = 60


@contextmanager
def server(*flags: str) -> Iterator[RunningServer]:
    """A server without the demo scene, rate limits lifted (the bench sends fast on purpose),
    and ``flags``."""
    running = start_server("--no-demo", *LIMITS, *flags)
    try:
        yield running
    finally:
        stop_server(running)


@contextmanager
def driving(running: RunningServer, scene: str, kind: str, count: int, seconds: float,
            nice: tuple[str, ...] = NICE) -> Iterator[subprocess.Popen[str]]:
    """A driver animating a scene (at most ``seconds``); entered once the scene is built,
    stopped on leaving."""
    process = subprocess.Popen([*nice, sys.executable, "-m", "bench.drive", running.ws, scene,
                                kind, str(count), str(seconds)], cwd=ROOT,
                               stdout=subprocess.PIPE, text=True)
    try:
        assert process.stdout is not None and json.loads(process.stdout.readline())["ready"]
        yield process
    finally:
        process.terminate()
        process.wait(timeout=30)


def ask(ws: Any, request: dict[str, Any], timeout: float = 60) -> dict[str, Any]:
    """Send a request and wait for its answer (frames skipped); it must be ok."""
    ws.send(json.dumps({**request, "id": 1}))
    while True:
        answer = json.loads(ws.recv(timeout=timeout))
        if answer.get("id") == 1 and answer["op"] in ("ok", "error"):
            assert answer["op"] == "ok", answer
            return answer


def tick_outside(running: RunningServer, count: int, seconds: float) -> dict[str, Any]:
    """hands-``count`` driven at 60 Hz: the server's own tick figures, its tick rate, and
    the CPU of the whole server (web process and scene process; no other scene ticks)."""
    scene = f"hands{count}"
    with driving(running, scene, "hands", count, seconds):
        time.sleep(seconds * 0.3)  # the driver's first steps, and the scene's first frames
        cpu_before, started = server_cpu_seconds(running, scene), time.monotonic()
        time.sleep(seconds * 0.6)
        cores = (server_cpu_seconds(running, scene) - cpu_before) / (time.monotonic() - started)
        metrics = running.figures(scene)
    return {"hands": count, "tick_ms_p50": metrics["tickMsP50"], "tick_ms_p95": metrics["tickMsP95"],
            "ticks_per_second": metrics["ticksPerSecond"], "cpu_percent": metrics["cpuPercent"],
            "server_cores": cores}


def latency(running: RunningServer, rounds: int) -> dict[str, Any]:
    """From one client's setAngle to another client's frame carrying it, ``rounds`` times."""
    scene = "latency"
    with connect(f"{running.ws}/ws?scene={scene}", max_size=None) as setter:
        me = json.loads(setter.recv(timeout=30))["client"]
        motor = f"{me}.m"
        build(setter, [{"op": "create", "object": f"{me}.r", "type": "Robot"},
                       {"op": "create", "object": motor, "type": "MotorZ"},
                       {"op": "create", "object": f"{me}.f", "type": "EdgedFinger"},
                       {"op": "call", "object": f"{me}.r", "method": "attachChain",
                        "args": [{"ref": motor}, {"ref": f"{me}.f"}]}])
        threading.Thread(target=drain, args=(setter,), daemon=True).start()
        with connect(f"{running.ws}/ws?scene={scene}&role=viewer", max_size=None) as watcher:
            times = [_one_change(setter, watcher, f"{me}.r", motor, k) for k in range(rounds)]
    period_ms = 1000 / 60
    result = figure(times)
    p99 = sorted(times)[max(0, math.ceil(0.99 * len(times)) - 1)]
    return {"rounds": rounds, "ms": result, "p99_ms": p99, "p99_in_periods": p99 / period_ms}


def _one_change(setter: Any, watcher: Any, robot: str, motor: str, k: int) -> float:
    """A frame sends all of a robot's angles: ``motor`` is ``robot``'s first."""
    angle = 0.001 * (k % 1000) + 0.0005
    time.sleep(random.uniform(0, 1 / 60))  # not in step with the ticks: any phase of one
    sent = time.monotonic()
    setter.send(json.dumps({"op": "call", "object": motor, "method": "setAngle", "args": [angle]}))
    while time.monotonic() < sent + STUCK_SECONDS:
        message = json.loads(watcher.recv(timeout=STUCK_SECONDS))
        if message["op"] == "frame" and message.get("angles", {}).get(robot, [None])[0] == angle:
            return (time.monotonic() - sent) * 1000
    raise TimeoutError(f"no frame carried angle {angle} of {motor} within {STUCK_SECONDS} s")


def viewers(running: RunningServer, counts: list[int], seconds: float) -> list[dict[str, Any]]:
    """Viewer connections on hands-10 while it is driven at 60 Hz: per count, frames per
    second (lowest, median), late frames, server CPU and the web process's CPU per
    viewer-frame; then the most viewers again with one more connection that never reads."""
    scene = "viewed"
    runs = [(count, False) for count in counts] + [(max(counts), True)]
    with driving(running, scene, "hands", 10, 3600) as driver:
        # a row whose driver had gone measured a scene nobody animated (smaller frames)
        return [{**_viewer_run(running, scene, count, seconds, stall),
                 "driver_lasted": driver.poll() is None} for count, stall in runs]


def _viewer_run(running: RunningServer, scene: str, count: int, seconds: float,
                stall: bool) -> dict[str, Any]:
    command = [*NICE, sys.executable, "-m", "bench.viewers", running.ws, scene, str(count),
               *(["--stalled"] if stall else [])]

    def window(start: float, end: float) -> tuple[float, dict[str, Any], dict[str, Any]]:
        """The server's cores over the window, and the scene's metrics at each end."""
        sleep_until(start)
        cpu, first = server_cpu_seconds(running, scene), running.figures(scene)
        sleep_until(end)
        cores = (server_cpu_seconds(running, scene) - cpu) / (time.monotonic() - start)
        return cores, first, running.figures(scene)

    [out], (cores, before, after) = run_viewers([command], seconds, window)
    found = out["viewers"]
    frames = sum(v["frames"] for v in found)
    fps = [v["fps"] for v in found]
    handed = after["viewerFrames"] - before["viewerFrames"]
    return {"viewers": count, "stalled": stall, "fps_min": min(fps),
            "fps_median": figure(fps).median,
            "late_pct": 100 * sum(v["late"] for v in found) / max(1, frames),
            "skipped_pct": 100 * sum(v["skipped"] for v in found) / max(1, frames),
            "server_cores": cores, "viewer_frames_per_s": handed / seconds,
            # the web process's fan-out, measured in it: CPU per frame handed to a connection
            "fanout_us_per_viewer_frame":
                1e6 * (after["fanoutCpuSeconds"] - before["fanoutCpuSeconds"]) / max(1, handed)}


def viewer_frame_us_outside(rows: list[dict[str, Any]]) -> float:
    """The server's whole CPU (web and scene processes) per viewer-frame, from outside:
    the most viewers' cores less the fewest's, over the frames the difference received."""
    plain = [row for row in rows if not row["stalled"]]
    fewest, most = min(plain, key=lambda r: r["viewers"]), max(plain, key=lambda r: r["viewers"])
    frames_per_s = most["viewer_frames_per_s"] - fewest["viewer_frames_per_s"]
    return 1e6 * (most["server_cores"] - fewest["server_cores"]) / max(1.0, frames_per_s)


def server_cpu_seconds(running: RunningServer, scene: str) -> float:
    """CPU seconds (user + system) of the server's own process and of the scene's process."""
    return cpu_seconds([running.process.pid, running.figures(scene)["pid"]])


def cpu_seconds(pids: list[int]) -> float:
    """User and system CPU seconds of these processes (those gone meanwhile count 0)."""
    ticks = 0
    for fields in filter(None, map(_stat, pids)):
        ticks += int(fields[11]) + int(fields[12])
    return ticks / 100  # clock ticks (USER_HZ, 100 on Linux)


def _stat(pid: int) -> list[str] | None:
    """The fields of /proc/<pid>/stat after the command's name (None once it is gone)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return None


QUIET_CORES = 0.05  # a server at rest: what is left of the last measure is done
QUIET_WINDOW_S = 0.5


def until_quiet(pids: Callable[[], list[int]], within: float = STUCK_SECONDS) -> float:
    """Wait until the processes ``pids()`` names use less than QUIET_CORES between them
    over QUIET_WINDOW_S; the seconds waited. What one measure leaves running must not be
    counted in the next: hands-100's scene, its driver gone, kept most of a core busy for
    10 s (measuring its still contacts every tick, until it slept without clients; mended
    since), and the clients' server CPU read 27 % after it, 22 % on a fresh server."""
    started = time.monotonic()
    while time.monotonic() < started + within:
        watched = pids()
        before = cpu_by_process(watched)
        time.sleep(QUIET_WINDOW_S)
        # (and none waiting for a core: on a saturated machine a busy process starved of
        # one used under QUIET_CORES for a window, and the suite's test of this failed)
        if cpu_since(before, cpu_by_process(watched)) < QUIET_CORES * QUIET_WINDOW_S \
                and not any(map(runnable, watched)):
            return time.monotonic() - started
    print(f"bench: the server did not come to rest within {within} s; measuring on",
          file=sys.stderr)  # (a lost hour's run would say less than a noted one)
    return time.monotonic() - started


def runnable(pid: int) -> bool:
    """Whether the process's main thread is running or waiting for a core (state R)."""
    fields = _stat(pid)
    return fields is not None and fields[0] == "R"


def server_processes(running: RunningServer) -> list[int]:
    """The server's own process and every scene's."""
    return [running.process.pid, *descendants(running.process.pid)]


def cpu_by_process(pids: list[int]) -> dict[int, float]:
    """Each process's CPU seconds so far (for :func:`cpu_since`)."""
    return {pid: cpu_seconds([pid]) for pid in pids}


def cpu_since(before: dict[int, float], now: dict[int, float]) -> float:
    """CPU seconds the processes of ``now`` spent since ``before`` (one that started
    meanwhile, all of its own): one that ended meanwhile is left out, rather than its
    whole life taken off the sum."""
    return sum(seconds - before.get(pid, 0.0) for pid, seconds in now.items())


def two_scenes(running: RunningServer, count: int, seconds: float) -> dict[str, Any]:
    """Two scenes of hands-``count`` driven at once: each one's tick and tick rate."""
    with driving(running, "busy1", "hands", count, seconds), \
            driving(running, "busy2", "hands", count, seconds):
        time.sleep(seconds * 0.9)
        found = [running.figures(name) for name in ("busy1", "busy2")]
    return {"hands": count, "ticks_per_second": [m["ticksPerSecond"] for m in found],
            "tick_ms_p50": [m["tickMsP50"] for m in found],
            "tick_ms_p95": [m["tickMsP95"] for m in found]}
