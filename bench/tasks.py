"""What the hand-function tasks cost, on one core: a grasp trial's scene seconds per CPU
second (``grasp_trial_realtime_x``: above 1 is faster than real time on one core) and
Box and Blocks' CPU seconds per scene second (``bb_cpu_per_scene_s``), each counting
every process of the server and the client (this process) that drives the task.
"""

from __future__ import annotations

import time
from typing import Any, Callable

import virtual_prosthetics as vp
from virtual_prosthetics.tasks import box_and_blocks, grasp
from virtual_prosthetics.tasks.hands import hand_source
from virtual_prosthetics.tasks.trial import TaskHand

from tests.conftest import RunningServer, start_server, stop_server

from .live import cpu_seconds
from .processes import descendants

TICK = 1 / 60


def _costed(running: RunningServer, run: Callable[[], Any]) -> tuple[float, float]:
    """CPU seconds (server, every process, and this client) and wall seconds of ``run``."""
    def cpu() -> float:
        return cpu_seconds([running.process.pid, *descendants(running.process.pid)]) + time.process_time()
    before, started = cpu(), time.perf_counter()
    run()
    return cpu() - before, time.perf_counter() - started


def measure(bb_seconds: float, blocks: int) -> dict[str, Any]:
    """One grasp trial (the edged hand, the ball light and heavy) and Box and Blocks for
    ``bb_seconds`` with ``blocks`` blocks, each in a scene of its own."""
    running = start_server("--no-demo")
    try:
        with vp.connect(running.ws, scene="bench-grasp") as session:
            hands = TaskHand(hand_source("edged", session))
            cpu, wall = _costed(running, lambda: grasp.grasp(session, hands, 1, seed=3,
                                                             patterns=["spherical"]))
        scene = 2 * (round(grasp.PHASES.end / TICK) + 1) * TICK  # two rows: light, heavy
        with vp.connect(running.ws, scene="bench-bb") as session:
            hands = TaskHand(hand_source("edged", session))
            bb_cpu, bb_wall = _costed(running, lambda: box_and_blocks.box_and_blocks(
                session, hands, 1, seconds=bb_seconds, blocks=blocks))
        bb_scene = bb_seconds + 2.0  # the heap settling and the last drop landing
        return {"grasp": {"scene_s": scene, "cpu_s": cpu, "wall_s": wall,
                          "realtime_x_one_core": scene / cpu, "realtime_x_wall": scene / wall},
                "box_and_blocks": {"scene_s": bb_scene, "blocks": blocks, "cpu_s": bb_cpu,
                                   "wall_s": bb_wall, "cpu_per_scene_s": bb_cpu / bb_scene}}
    finally:
        stop_server(running)
