"""The benchmark runner: ``make bench`` (every figure, a few minutes) and ``make bench-quick``
(the same code on tiny scenes, under a minute, in the test suite; no figure is judged).

Writes ``results.json`` (the headline figures by name, then every measure in full) and
``RESULTS.md``'s generated section (between its markers; the notes below it stay).
``python -m bench.run [--quick] [--out DIR]``.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from . import (busy_connect, chaos, chaos_cluster, client_cpu, cluster, core, fanout_floor, gym,
               idle_scenes, live, piles, recording, scenes, tasks)
from .report import lines, write

HERE = Path(__file__).resolve().parent
# bench-quick's measures through servers, at most this many at once (51 s alone with all six,
# 62 s with three): six start six servers within a second beside the suite's other long
# files, and a reconnection test then missed its window once
SIDE_BY_SIDE = 3
# the measures through servers, the longest first (a quick run's seconds: 33, 28, 19, 18…)
QUICK_ORDER = ("chaos", "cluster", "chaos_cluster", "outside", "tasks", "piles", "gym",
               "idle_scenes")

# a quick run's server drops a gone driver's robots after a second, not the default ten:
# each measure waits for the server to be at rest first, and in the suite those waits were
# half of the measures through one server (33 of 59 s), the robots ticking meanwhile
QUICK_GRACE = ("--limit", "leaveGraceSeconds=1")


@dataclass(frozen=True)
class Sizes:
    """How much of each measure a run does."""

    ticks: int
    hands_large: int
    sensor_counts: tuple[int, ...]
    sensing_ticks: int
    requests: int
    frames: int
    hand_counts: tuple[int, ...]
    hand_ticks: int
    outside_seconds: float
    latency_rounds: int
    viewer_counts: tuple[int, ...]
    viewer_seconds: float  # quick: 2 s (in 0.5 s a niced viewer beside the suite once got under 2 frames)
    busy_hands: int
    document_rounds: int
    chaos_faults: int
    cluster_chaos_faults: int  # bus kills and worker kills (bench/chaos_cluster.py)
    idle_scenes: int
    hands_most: int  # driven from outside by one client: the 100 hands
    dynamic: tuple[int, int, int, int]  # hands, free objects, ticks while they fall, ticks at rest
    recorded_ticks: int  # of hands-10 recorded (10 minutes: the seek figure's recording)
    seeks: int  # to random times of it
    cluster_viewers: tuple[int, ...]  # light viewers of one scene, over one gateway and two
    cluster_busy: int  # busy scenes placed over two workers
    cluster_objects: int  # kept objects of the scene whose worker is killed
    cluster_idle_wait: float  # seconds for the busy scenes to go before that
    loaded_scenes: int  # animated while a script connects (busy_connect)
    piles: tuple[int, int, float]  # balls made in one spot, boxes in a tower, seconds watched
    # Box and Blocks' scene seconds and blocks, grasp trials side by side, runs of one trial
    # (bench/tasks.py)
    tasks: tuple[float, int, int, int]
    gym: tuple[int, int]  # environment steps and resets measured (bench/gym.py)


FULL = Sizes(ticks=600, hands_large=50, sensor_counts=(100, 1000), sensing_ticks=200,
             requests=20_000, frames=300, hand_counts=(10, 20, 30, 40, 50, 60, 80, 100),
             hand_ticks=120, outside_seconds=12, latency_rounds=2000,
             viewer_counts=(1, 10, 100, 1000), viewer_seconds=5, busy_hands=20,
             document_rounds=30, chaos_faults=30 * len(chaos.KINDS),
             cluster_chaos_faults=5 * len(chaos_cluster.KINDS), idle_scenes=200, hands_most=100,
             dynamic=(10, 50, 240, 300), recorded_ticks=36_000, seeks=50,
             cluster_viewers=(500, 750, 875, 1000, 1125, 1250, 2000), cluster_busy=200, cluster_objects=50,
             cluster_idle_wait=20.0, loaded_scenes=13, piles=(2000, 300, 180.0),
             tasks=(20.0, 150, 10, 3), gym=(600, 30))
QUICK = Sizes(ticks=5, hands_large=3, sensor_counts=(4,), sensing_ticks=3, requests=50,
              frames=3, hand_counts=(2, 3), hand_ticks=3, outside_seconds=1.5,
              latency_rounds=5, viewer_counts=(1, 3), viewer_seconds=2.0, busy_hands=2,
              document_rounds=2, chaos_faults=len(chaos.KINDS),
              cluster_chaos_faults=len(chaos_cluster.KINDS), idle_scenes=3, hands_most=4,
              dynamic=(2, 4, 3, 3), recorded_ticks=5, seeks=2,
              cluster_viewers=(2,), cluster_busy=2, cluster_objects=3, cluster_idle_wait=0.0,
              loaded_scenes=2, piles=(60, 10, 1.5), tasks=(1.0, 20, 1, 1), gym=(6, 2))


def measure(sizes: Sizes) -> dict[str, Any]:
    """Every measure, in-process first (quiet machine), then through servers (``QUICK``: the
    measures through servers side by side, since they mostly wait)."""
    small, large = (10, sizes.hands_large) if sizes is FULL else (2, sizes.hands_large)
    found: dict[str, Any] = {}

    def hands(count: int, idle: float = 0.0) -> Callable[[], Any]:
        return lambda: core.tick_against_floor(f"hands-{count}", scenes.hands("c1", count),
                                               lambda n: scenes.hand_step("c1", count, n),
                                               sizes.ticks, idle)
    steps = {
        "hands10": hands(small),
        "hands10_idle": hands(small, idle=core.PERIOD),
        "hands50": hands(large),
        "arms11": lambda: core.tick_against_floor(
            "arms-11", scenes.arms("c1"), lambda n: scenes.arm_step("c1", n), sizes.ticks),
        "sensors": lambda: [core.sensing(small, count, sizes.sensing_ticks)
                            for count in sizes.sensor_counts],
        "requests": lambda: core.requests(sizes.requests),
        "frames": lambda: core.frame_bytes(sizes.frames),
        "max_hands": lambda: core.max_hands(list(sizes.hand_counts), sizes.hand_ticks),
        "documents": lambda: [core.documents(count, sizes.document_rounds)
                              for count in (small, large)],
        "dynamic": lambda: core.dynamic(*sizes.dynamic),
        "recording": lambda: recording.recording(small, sizes.recorded_ticks, sizes.seeks),
        "fanout_floor": lambda: fanout_floor.send_floor_us(max(sizes.viewer_counts),
                                                           sizes.viewer_seconds),
    }
    for name, step in steps.items():
        found[name] = _timed(name, step)
    served: dict[str, Callable[[], Any]] = {
        "outside": lambda: _outside(sizes, small, large),
        "piles": lambda: piles.measure(*sizes.piles),
        "tasks": lambda: tasks.measure(*sizes.tasks),
        "gym": lambda: gym.measure(*sizes.gym),
        "chaos": lambda: chaos.run(sizes.chaos_faults, quick=sizes is QUICK),
        "chaos_cluster": lambda: chaos_cluster.run(sizes.cluster_chaos_faults,
                                                   quick=sizes is QUICK),
        "idle_scenes": lambda: idle_scenes.measure(sizes.idle_scenes, sizes.outside_seconds),
        "cluster": lambda: cluster.measure(list(sizes.cluster_viewers), sizes.viewer_seconds,
                                           sizes.cluster_busy, sizes.cluster_objects,
                                           sizes.cluster_idle_wait),
    }
    if sizes is QUICK:  # each its own servers, mostly waiting on them: side by side
        with ThreadPoolExecutor(SIDE_BY_SIDE) as pool:  # the longest first: the run ends sooner
            futures = {name: pool.submit(_timed, name, served[name])
                       for name in sorted(served, key=QUICK_ORDER.index)}  # (each listed)
            done = {name: future.result() for name, future in futures.items()}
    else:  # one at a time, each on a quiet machine
        done = {name: _timed(name, step) for name, step in served.items()}
    found.update(done.pop("outside"))
    return found | done


def _outside(sizes: Sizes, small: int, large: int) -> dict[str, Any]:
    """The measures through one server: ticks driven from outside, latency, viewers."""
    with live.server(*(QUICK_GRACE if sizes is QUICK else ())) as running:
        outside = {
            "outside": lambda: [live.tick_outside(running, count, sizes.outside_seconds)
                                for count in (small, large, sizes.hands_most)],
            "clients": lambda: [client_cpu.measure(running, client, small, sizes.outside_seconds)
                                for client in ("python", "js")],
            "latency": lambda: live.latency(running, sizes.latency_rounds),
            "viewers": lambda: live.viewers(running, list(sizes.viewer_counts),
                                            sizes.viewer_seconds),
            "two_scenes": lambda: live.two_scenes(running, sizes.busy_hands,
                                                  sizes.outside_seconds),
            "busy_connect": lambda: busy_connect.measure(
                running, sizes.loaded_scenes, 2, min(5, sizes.latency_rounds), 600),
        }
        found = {}
        for name, step in outside.items():  # each on a server at rest
            live.until_quiet(lambda: live.server_processes(running))
            found[name] = step()
        return found


def _timed(name: str, step: Callable[[], Any]) -> Any:
    started = time.monotonic()
    result = step()  # one line when done: measures side by side would interleave two
    print(f"{name}: {time.monotonic() - started:.1f} s", file=sys.stderr, flush=True)
    return result


def headline(found: dict[str, Any], commit: str) -> dict[str, Any]:
    """The named figures of results.json."""
    most = [row for row in found["viewers"]
            if row["viewers"] == max(r["viewers"] for r in found["viewers"])]
    return {
        "tick_ratio_hands10": found["hands10"]["ratio"],
        "tick_ratio_hands10_idle": found["hands10_idle"]["ratio"],
        "tick_ratio_hands50": found["hands50"]["ratio"],
        "sensors100_ms": found["sensors"][0]["sensing_ms"].median,
        "sensors100_ratio": found["sensors"][0]["ratio"],
        "requests_per_s": found["requests"]["per_second"],
        "latency_p99_ms": found["latency"]["p99_ms"],
        "viewers1000_fps_min": min(row["fps_min"] for row in most),
        "viewers1000_late_pct": max(row["late_pct"] for row in most),
        "viewer_frame_us": next(row["fanout_us_per_viewer_frame"] for row in most
                                if not row["stalled"]),
        "viewer_frame_us_outside": live.viewer_frame_us_outside(found["viewers"]),
        "viewer_frame_floor_us": found["fanout_floor"],
        "frame_bytes_two_hands": found["frames"]["frame_bytes"].median,
        "max_hands_60hz": found["max_hands"]["max_hands"],
        "dynamic_hands10_objects50_tick_ms": found["dynamic"]["tick_ms"].median,
        "dynamic_hands10_objects50_stepping_ms": found["dynamic"]["stepping_ms"].median,
        "recording_hands10_mb_per_minute": found["recording"]["mb_per_minute"],
        "recording_seek_ms_max": found["recording"]["seek_max_ms"],
        "server_cpu_hands10_pct": 100 * found["outside"][0]["server_cores"],
        "client_cpu_hands10_pct": 100 * found["clients"][0]["server_cores"],
        "client_cpu_hands10_js_pct": 100 * found["clients"][1]["server_cores"],
        "hands100_outside_ticks_per_s": found["outside"][2]["ticks_per_second"],
        "two_scenes_fps_min": min(found["two_scenes"]["ticks_per_second"]),
        "busy_server_connect_s": found["busy_connect"]["connect_fresh_s"].p95,
        "idle_scenes_server_cpu_pct": found["idle_scenes"]["server_cpu_pct"],
        "idle_scene_mb": found["idle_scenes"]["scene_pss_mb"].median,
        "pile2000_tick_ms_max": found["piles"]["balls"]["tick_ms_max"],
        "pile2000_ticks_per_s_after_5s": found["piles"]["balls"]["ticks_per_s_min_after_5s"],
        "pile2000_ticks_per_s_settled": found["piles"]["balls"]["ticks_per_s_end"],
        "pile2000_viewer_fps_min": found["piles"]["balls"]["viewer_fps_min"],
        "tower300_tick_ms_max": found["piles"]["tower"]["tick_ms_max"],
        "chaos_faults": found["chaos"]["faults"],
        "chaos_changes_lost": found["chaos"]["lost"],
        "chaos_bystander_gap_ms": found["chaos"]["worst_gap_ms"],
        "cluster_chaos_changes_lost": found["chaos_cluster"]["lost"],
        "bus_away_read_answered_s": found["chaos_cluster"]["read_answered_worst_s"],
        **cluster.headline(found["cluster"]),
        "grasp_trial_realtime_x": found["tasks"]["grasp"]["realtime_x_one_core"],
        "grasp_batch_trial_realtime_x": found["tasks"]["grasp_batch"]["realtime_x_one_core"],
        "bb_cpu_per_scene_s": found["tasks"]["box_and_blocks"]["cpu_per_scene_s"],
        "gym_steps_per_s": found["gym"]["steps_per_s"],
        "gym_vector2_speedup": found["gym"]["vector2_speedup"],
        "gym_reset_ms": found["gym"]["reset_ms"],
        "gym_step_overhead": found["gym"]["step_overhead"],
        "commit": commit,
    }


def commit() -> str:
    """The commit measured (with ``+changes`` when the work tree differs from it);
    ``unknown`` outside a git checkout (the container image has no history)."""
    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=HERE, capture_output=True,
                              text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               cwd=HERE, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("+changes" if dirty else "")


def main(argv: list[str]) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="tiny scenes: checks the code only")
    parser.add_argument("--out", type=Path, default=HERE, help="where to write the results")
    options = parser.parse_args(argv)
    started = time.monotonic()
    found = measure(QUICK if options.quick else FULL)
    results = {**headline(found, commit()), "quick": options.quick,
               "seconds": round(time.monotonic() - started, 1), "figures": core.as_json(found)}
    options.out.mkdir(parents=True, exist_ok=True)
    (options.out / "results.json").write_text(json.dumps(results, indent=1) + "\n")
    write(options.out / "RESULTS.md", lines(results, found))
    print(json.dumps({k: v for k, v in results.items() if k != "figures"}, indent=1))


if __name__ == "__main__":
    main(sys.argv[1:])
