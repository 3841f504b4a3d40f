"""What scenes nobody uses cost: memory, CPU, and how fast the server still answers.

A server with ``count`` scenes that clients opened and left (each scene's process then
stops ticking and waits): the proportional memory (PSS) of the scene processes, the CPU
of the whole server (every process) over a few seconds, how long a new client waits for
its ``hello`` on a fresh scene and on a running one, and the CPU a fresh scene's process
took to start (until that hello). These figures set the default
``scenes`` limit (server/core/kit/limits.py).
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

from websockets.sync.client import connect

from tests.conftest import RunningServer, eventually, start_server, stop_server

from .live import cpu_seconds, server_processes
from .stats import figure

def pss_mb(pid: int) -> float:
    """Proportional set size: private memory plus a share of what is shared (forked)."""
    for line in Path(f"/proc/{pid}/smaps_rollup").read_text().splitlines():
        if line.startswith("Pss:"):
            return int(line.split()[1]) / 1024
    return 0.0


def hello_ms(running: RunningServer, scene: str) -> float:
    """From connecting to the ``hello`` of a scene (started for it if it is new)."""
    started = time.perf_counter()
    with connect(f"{running.ws}/ws?scene={scene}", open_timeout=60) as ws:
        assert json.loads(ws.recv(timeout=60))["op"] == "hello"
        elapsed = (time.perf_counter() - started) * 1000
    return elapsed


def measure(count: int, seconds: float) -> dict[str, Any]:
    """Open ``count`` scenes, leave them, and measure the server once they all sleep."""
    # empty scenes without clients are removed after sceneIdleSeconds: here they stay for
    # the whole measure, however long opening them all takes on the day
    running = start_server("--no-demo", "--limit", f"scenes={count + 20}",
                           "--limit", "leaveGraceSeconds=1", "--limit", "sceneIdleSeconds=3600")
    try:
        opened = [hello_ms(running, f"idle{k}") for k in range(count)]
        eventually(lambda: _asleep(running) >= count, timeout=120)
        processes = server_processes(running)
        scene_pids = [m["pid"] for m in running.get("/api/metrics")["scenes"].values()]
        memory = [pss_mb(pid) for pid in scene_pids]
        before = cpu_seconds(processes)
        time.sleep(seconds)
        cpu = cpu_seconds(processes) - before
        hellos = min(10, count)  # a few of each kind (the idle ones that were opened)
        fresh = [hello_ms(running, f"fresh{k}") for k in range(hellos)]
        started = running.get("/api/metrics")["scenes"]
        start_cpu = [1000 * cpu_seconds([started[f"fresh{k}"]["pid"]]) for k in range(hellos)]
        again = [hello_ms(running, f"idle{k}") for k in range(hellos)]
        return {"scenes": count, "open_hello_ms": figure(opened),
                "scene_start_cpu_ms": figure(start_cpu),
                "scene_pss_mb": figure(memory), "scenes_pss_mb": sum(memory),
                "server_cpu_pct": 100 * cpu / seconds,
                "hello_new_scene_ms": figure(fresh), "hello_idle_scene_ms": figure(again)}
    finally:
        stop_server(running)


def _asleep(running: RunningServer) -> int:
    """Scenes whose process said it stopped ticking (silent without owing anything)."""
    scenes = running.get("/api/metrics")["scenes"].values()
    return sum(1 for m in scenes if m.get("clients") == 0 and m.get("asleep"))
