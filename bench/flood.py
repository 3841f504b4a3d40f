"""Load run: one client floods a scene while a viewer in another process watches another.

The flood: 100 EdgedHands in one batch, 400 Boxes in one spot in a second batch (every
pair overlaps), a 10 000-op batch, then 20 000 small messages as fast as the socket
takes them. The viewer (a separate process, so the flooder's own work cannot delay it)
records when each frame of its scene arrives. The flooding client runs in a process
of its own at the lowest priority (see ``flood_elsewhere``). Memory is the proportional set size (PSS)
of the server and every process under it, before, at the peak, after the flooder left
and after its scene was removed. The baseline is taken after a first flood of another
scene (since removed): that one grows the server's allocator pools once, for good.

The frame gaps counted are those of frames that arrive while a flood runs (both floods,
until a second after each one's last answer): a scene's first frames, before any flood,
come while its process is still starting.

Run twice: with the shipped limits, and with the rate limits lifted, so that the
isolation of scenes is measured without the rates' help.
"""

from __future__ import annotations

import json
import subprocess
import sys
import threading
import time
from pathlib import Path

from websockets.sync.client import connect

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from tests.conftest import start_server, stop_server  # noqa: E402

from bench.processes import descendants  # noqa: E402

VIEWER = """
import json, sys, time
from websockets.sync.client import connect
arrivals = []
with connect(sys.argv[1], max_size=None) as ws:
    end = time.monotonic() + float(sys.argv[2])
    while time.monotonic() < end:
        message = json.loads(ws.recv(timeout=10))
        if message["op"] == "frame":
            arrivals.append((time.monotonic(), message["time"]))
print(json.dumps(arrivals))
"""
IDLE_SECONDS = 3
UNLIMITED = ("--limit", "bytesPerSecond=1000000000")


def tree_pss_mb(pid: int) -> float:
    """PSS of ``pid`` and its descendants, in MB (shared pages counted once overall)."""
    total = 0
    for current in [pid, *descendants(pid)]:
        try:
            rollup = Path(f"/proc/{current}/smaps_rollup").read_text()
        except OSError:
            continue
        total += next(int(line.split()[1]) for line in rollup.splitlines()
                      if line.startswith("Pss:"))
    return total / 1024


def flood(ws_url: str, scene: str = "flooded") -> tuple[float, dict[str, int]]:
    """Send the flood and wait for its last answer; seconds taken and answers by kind."""
    with connect(f"{ws_url}/ws?scene={scene}", max_size=None) as ws:
        me = json.loads(ws.recv())["client"]
        ws.recv()
        started = time.monotonic()
        ws.send(json.dumps({"op": "batch", "id": 1, "ops": [
            {"op": "create", "object": f"{me}.h{k}", "type": "EdgedHand"} for k in range(100)]}))
        ws.send(json.dumps({"op": "batch", "id": 2, "ops": [
            {"op": "create", "object": f"{me}.b{k}", "type": "Box"} for k in range(400)]}))
        ws.send(json.dumps({"op": "batch", "id": 3, "ops": [
            {"op": "call", "object": f"{me}.b{k % 400}", "method": "setPosition",
             "args": [k % 3, 0, 0]} for k in range(10_000)]}))
        for k in range(20_000):
            ws.send(json.dumps({"op": "call", "object": f"{me}.b1", "method": "setPosition",
                                "args": [k % 7, 0, 0], "id": 10 + k}))
        ws.send(json.dumps({"op": "ping", "id": 5}))
        kinds: dict[str, int] = {}
        while True:
            message = json.loads(ws.recv(timeout=300))
            if message.get("id") == 5:
                return time.monotonic() - started, kinds
            if message["op"] in ("ok", "error"):
                kind = message["op"] if message["op"] == "ok" else message["code"]
                kinds[kind] = kinds.get(kind, 0) + 1


def flood_elsewhere(ws_url: str, scene: str = "flooded") -> tuple[float, dict[str, int]]:
    """``flood`` from a process of its own at the lowest CPU priority.

    The flooding client would be on another machine; here it shares two cores with the
    server, and at normal priority its own work (encoding 30 000 messages) takes the
    cores the server needs. Lowered, it still sends as fast as the server takes them.
    """
    done = subprocess.run(["nice", "-n", "19", sys.executable, __file__, "--flood", ws_url, scene],
                          stdout=subprocess.PIPE, text=True, check=True)
    seconds, kinds = json.loads(done.stdout)
    return seconds, kinds


def frame_gaps(arrivals: list[list[float]], windows: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """(arrival gap, scene-clock gap) in ms, for each frame that arrived inside a window."""
    return sorted(((b[0] - a[0]) * 1000, (b[1] - a[1]) * 1000)
                  for a, b in zip(arrivals, arrivals[1:])
                  if any(start <= b[0] <= end for start, end in windows))


def timed_flood(ws_url: str, scene: str, windows: list[tuple[float, float]]) -> tuple[float, dict[str, int]]:
    """A flood, its window (start to one second after its last answer) noted in ``windows``."""
    started = time.monotonic()
    result = flood_elsewhere(ws_url, scene)
    windows.append((started, time.monotonic() + 1))
    return result


def run(label: str, *args: str) -> dict[str, object]:
    server = start_server("--no-demo", "--limit", f"sceneIdleSeconds={IDLE_SECONDS}", *args)
    windows: list[tuple[float, float]] = []
    try:
        viewer = subprocess.Popen(
            [sys.executable, "-c", VIEWER, f"{server.ws}/ws?scene=watched&role=viewer", "60"],
            stdout=subprocess.PIPE, text=True)
        time.sleep(2)  # the watched scene's process has started and ticks
        timed_flood(server.ws, "warm-up", windows)  # grows the server's pools for good
        time.sleep(IDLE_SECONDS + 6)  # that scene was made and removed: the baseline
        baseline = tree_pss_mb(server.process.pid)
        peak = [baseline]
        sampling = True

        def sample() -> None:
            while sampling:
                peak.append(tree_pss_mb(server.process.pid))
                time.sleep(0.5)
        sampler = threading.Thread(target=sample)
        sampler.start()
        seconds, kinds = timed_flood(server.ws, "flooded", windows)
        flooded_metrics = server.get("/api/metrics")["scenes"]["flooded"]
        time.sleep(1)
        after_leave = tree_pss_mb(server.process.pid)
        time.sleep(IDLE_SECONDS + 6)
        sampling = False
        sampler.join()
        after_removal = tree_pss_mb(server.process.pid)
        arrivals = json.loads(viewer.communicate(timeout=120)[0])
    finally:
        stop_server(server)
    gaps = frame_gaps(arrivals, windows)
    return {"label": label, "flood_s": seconds, "answers": kinds, "frames": len(gaps),
            "gap_max_ms": gaps[-1][0], "gap_max_scene_clock_ms": gaps[-1][1],
            "gap_p99_ms": gaps[int(len(gaps) * 0.99)][0], "gap_median_ms": gaps[len(gaps) // 2][0],
            "flooded_tick_max_ms": flooded_metrics["tickMsMax"], "pss_baseline_mb": baseline,
            "pss_peak_mb": max(peak), "pss_after_leave_mb": after_leave,
            "pss_after_removal_mb": after_removal}


def main() -> None:
    if sys.argv[1:2] == ["--flood"]:
        print(json.dumps(flood(*sys.argv[2:4])))
        return
    for result in (run("shipped limits"), run("rates lifted", *UNLIMITED)):
        print(json.dumps(result))


if __name__ == "__main__":
    main()
