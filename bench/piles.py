"""Piles in a dynamic scene, through a real server: balls made in one spot in one batch, and a
tower of boxes; how the scene ticks from the burst until it settles, what its viewer gets,
and how big its process grows. ``python -m bench.piles BALLS BOXES SECONDS`` (JSON out).
"""

from __future__ import annotations

import json
import sys
import threading
import time
from pathlib import Path
from typing import Any

from websockets.sync.client import connect

from .live import ask, server

SAMPLE_SECONDS = 0.5
STILL_SECONDS = 5.0  # with no frame moving anything: settled


def measure(balls: int, boxes: int, seconds: float) -> dict[str, Any]:
    """Both piles, each in a scene of its own on one server, each watched until it has
    been still for STILL_SECONDS (at most ``seconds``)."""
    with server() as running:
        return {"balls": pile(running, "balls", balls, seconds),
                "tower": pile(running, "tower", boxes, seconds)}


def pile_batch(me: str, kind: str, count: int) -> list[dict[str, Any]]:
    """The ops of one batch making a pile (``kind``: balls or tower) of client ``me``'s."""
    if kind == "balls":  # made at one point: a radius of 0.2, at 2 m
        return [op for k in range(count) for op in (
            {"op": "create", "object": f"{me}.{k}", "type": "Ball", "args": [0.2]},
            {"op": "call", "object": f"{me}.{k}", "method": "setPosition", "args": [0, 2, 0]})]
    return [op for k in range(count) for op in (  # stacked, each on the one below
        {"op": "create", "object": f"{me}.{k}", "type": "Box", "args": [0.5, 0.5, 0.5]},
        {"op": "call", "object": f"{me}.{k}", "method": "setPosition", "args": [0, 0.26 + 0.5 * k, 0]})]


class _Viewer(threading.Thread):
    """A viewer of the scene: when each frame came, and the last that moved something."""

    def __init__(self, url: str) -> None:
        super().__init__(daemon=True)
        self.url, self.frames, self.last_moving, self.stop = url, [], 0.0, False

    def run(self) -> None:
        with connect(self.url + "&role=viewer", max_size=None) as ws:
            while not self.stop:
                message = ws.recv(timeout=300)
                if message.startswith('{"op":"frame"'):
                    now = time.monotonic()
                    self.frames.append(now)
                    if '"poses"' in message:
                        self.last_moving = now


def pile(running: Any, kind: str, count: int, seconds: float) -> dict[str, Any]:
    """Make the pile, then sample the scene's figures every SAMPLE_SECONDS for ``seconds``."""
    scene = f"piles-{kind}"
    url = f"{running.ws}/ws?scene={scene}"
    with connect(url, max_size=None, max_queue=None) as ws:
        me = json.loads(ws.recv(timeout=30))["client"]
        ask(ws, {"op": "call", "object": "scene", "method": "setPhysics", "args": ["dynamic"]})
        viewer = _Viewer(url)
        viewer.start()
        time.sleep(1.0)
        burst = time.monotonic()
        ask(ws, {"op": "batch", "ops": pile_batch(me, kind, count)}, timeout=300)
        answered = time.monotonic() - burst
        samples = []
        while time.monotonic() < burst + seconds and (
                time.monotonic() < burst + min(seconds, 2 * STILL_SECONDS)
                or time.monotonic() - max(viewer.last_moving, burst) < STILL_SECONDS):
            time.sleep(SAMPLE_SECONDS)
            samples.append(_sample(running, scene, burst))
        viewer.stop = True
    return _figures(kind, count, answered, samples, viewer, burst)


def _sample(running: Any, scene: str, burst: float) -> dict[str, Any]:
    figures = running.figures(scene)
    return {"t": time.monotonic() - burst, "ticks": figures["ticks"],
            "tick_ms_max": figures["tickMsMax"], "rss_mb": _rss_mb(figures["pid"])}


def _rss_mb(pid: int) -> float:
    """The resident memory of the scene's process (MB)."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return 0.0


def _rate(samples: list[dict[str, Any]], start: float, end: float) -> float:
    """Ticks a second between two times after the burst (the samples nearest them)."""
    first = min(samples, key=lambda s: abs(s["t"] - start))
    last = min(samples, key=lambda s: abs(s["t"] - end))
    if last["t"] <= first["t"]:
        first, last = samples[-2:] if len(samples) > 1 else (samples[0], samples[0])
    return (last["ticks"] - first["ticks"]) / max(last["t"] - first["t"], 1e-9)


def _figures(kind: str, count: int, answered: float, samples: list[dict[str, Any]],
             viewer: _Viewer, burst: float) -> dict[str, Any]:
    frames = [t - burst for t in viewer.frames if t > burst]
    gaps = [b - a for a, b in zip(frames, frames[1:])]
    per_second = [sum(1 for t in frames if k <= t < k + 1) for k in range(int(frames[-1]))] \
        if frames else [0]
    span = samples[-1]["t"]
    return {"kind": kind, "count": count, "batch_answered_s": round(answered, 3),
            "tick_ms_max": round(max(s["tick_ms_max"] for s in samples), 1),
            "ticks_per_s_at_5s": round(_rate(samples, 5.0, 6.0), 1),
            "ticks_per_s_min_after_5s": round(min(
                (_rate(samples, t, t + 1.0) for t in range(5, int(span) - 1)),
                default=_rate(samples, 0.0, span)), 1),
            "ticks_per_s_end": round(_rate(samples, span - 2.0, span), 1),
            "settled_s": round(viewer.last_moving - burst, 1),  # its last frame that moved anything
            "viewer_gap_ms_max": round(1000 * max(gaps, default=0.0)),
            "viewer_fps_min": min(per_second, default=0),
            "rss_mb_max": round(max(s["rss_mb"] for s in samples)), "seconds": round(span, 1)}


if __name__ == "__main__":
    print(json.dumps(measure(int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3])), indent=1))
