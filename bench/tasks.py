"""What the hand-function tasks cost, on one core: a grasp trial's scene seconds per CPU
second (``grasp_trial_realtime_x``: above 1 is faster than real time on one core), alone
and as the command line runs trials, ten side by side in one scene
(``grasp_batch_trial_realtime_x``: a trial's share of the row's CPU), and Box and Blocks'
CPU seconds per scene second (``bb_cpu_per_scene_s``), each counting every process of
the server and the client (this process) that drives the task.
"""

from __future__ import annotations

import time
from typing import Any, Callable

import virtual_prosthetics as vp
from virtual_prosthetics.tasks import box_and_blocks, grasp
from virtual_prosthetics.tasks.hands import hand_source
from virtual_prosthetics.tasks.trial import TaskHand

from tests.conftest import RunningServer, start_server, stop_server

from .live import cpu_by_process, cpu_since, server_processes

TICK = 1 / 60


def _costed(running: RunningServer, run: Callable[[], Any]) -> tuple[float, float]:
    """CPU seconds (server, every process, and this client) and wall seconds of ``run``.

    Counted per process (:func:`cpu_since`): a sum over the processes alive at each end
    lost the whole CPU of a scene that ended meanwhile (the ten-trial grasp's, stopped
    once idle, took 50 CPU-s off Box and Blocks' figure, which read 0.38, not 0.56)."""
    def cpu() -> dict[int, float]:
        return cpu_by_process(server_processes(running))
    before, mine, started = cpu(), time.process_time(), time.perf_counter()
    run()
    return cpu_since(before, cpu()) + time.process_time() - mine, time.perf_counter() - started


def measure(bb_seconds: float, blocks: int, batch: int = 10, repeats: int = 3) -> dict[str, Any]:
    """One grasp trial (the edged hand, the ball light and heavy) ``repeats`` times, the
    run of the median speed kept (one run of 13 scene-s swung from 2.3× to 3.8× on a
    shared 2-core machine); ``batch`` of them side by side; Box and Blocks for
    ``bb_seconds`` with ``blocks`` blocks: each in a scene of its own."""
    running = start_server("--no-demo")
    try:
        runs = sorted((_grasp(running, 1, k) for k in range(repeats)),
                      key=lambda run: run["realtime_x_one_core"])
        one = {**runs[len(runs) // 2], "runs_realtime_x": [r["realtime_x_one_core"] for r in runs]}
        row = one if batch == 1 else _grasp(running, batch)  # the quick bench's: no second run
        with vp.connect(running.ws, scene="bench-bb") as session:
            hands = TaskHand(hand_source("edged", session))
            bb_cpu, bb_wall = _costed(running, lambda: box_and_blocks.box_and_blocks(
                session, hands, 1, seconds=bb_seconds, blocks=blocks))
        bb_scene = bb_seconds + 2.0  # the heap settling and the last drop landing
        return {"grasp": one, "grasp_batch": row,
                "box_and_blocks": {"scene_s": bb_scene, "blocks": blocks, "cpu_s": bb_cpu,
                                   "wall_s": bb_wall, "cpu_per_scene_s": bb_cpu / bb_scene}}
    finally:
        stop_server(running)


def _grasp(running: RunningServer, trials: int, run: int = 0) -> dict[str, Any]:
    """The cost of ``trials`` grasp trials of the edged hand's spherical grip, run side by
    side in a scene of their own (the light ball's row, then the heavy's), per trial."""
    with vp.connect(running.ws, scene=f"bench-grasp-{trials}-{run}") as session:
        hands = TaskHand(hand_source("edged", session))
        cpu, wall = _costed(running, lambda: grasp.grasp(session, hands, trials, seed=3,
                                                         patterns=["spherical"]))
    scene = trials * 2 * (round(grasp.PHASES.end / TICK) + 1) * TICK  # two rows each
    return {"trials": trials, "scene_s": scene, "cpu_s": cpu, "wall_s": wall,
            "realtime_x_one_core": scene / cpu, "realtime_x_wall": scene / wall}
