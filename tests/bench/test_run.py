"""`make bench-quick`: the whole benchmark on tiny scenes, so its code keeps working.

It asserts what the run wrote, never how fast anything was.
"""

import json
import math
import subprocess

import pytest

from bench.report import BEGIN, END, TARGETS
from bench.run import commit
from tests.conftest import ROOT

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first


# The whole bench on tiny scenes (its measures through servers three at a time): 62 s alone on
# a 2-core machine; its own hang guard leaves room for a machine several times slower.
@pytest.mark.timeout(900)
def test_bench_quick_writes_every_figure(tmp_path):
    run = subprocess.run(["make", "-s", "bench-quick", f"BENCH_OUT={tmp_path}"], cwd=ROOT,
                         capture_output=True, text=True, timeout=850)
    assert run.returncode == 0, run.stderr[-6000:]  # what failed, in the test's report
    results = json.loads((tmp_path / "results.json").read_text())
    for name in TARGETS:
        assert isinstance(results[name], (int, float)) and math.isfinite(results[name]), name
    assert results["commit"] == commit() and results["quick"] is True  # "unknown" without git
    figures = results["figures"]
    assert [(d["hands"], d["export_ms"]["count"]) for d in figures["documents"]] == [(2, 2), (3, 2)]
    assert figures["hands10"]["bodies"] == 32 and figures["frames"]["frame_bytes"]["count"] == 3
    idle = figures["hands10_idle"]  # the same ticks, each after a period's sleep
    assert idle["idle_s"] == pytest.approx(1 / 60) and idle["tick_ms"]["count"] == 5
    assert math.isfinite(results["tick_ratio_hands10_idle"])
    assert [(row["viewers"], row["stalled"]) for row in figures["viewers"]] == [
        (1, False), (3, False), (3, True)]
    assert all(row["fps_median"] > 0 for row in figures["viewers"])  # frames reached them
    assert all(row["fanout_us_per_viewer_frame"] > 0 for row in figures["viewers"])  # counted
    assert math.isfinite(results["viewer_frame_us_outside"])
    assert figures["latency"]["rounds"] == 5
    assert [(c["client"], c["hands"]) for c in figures["clients"]] == [("python", 2), ("js", 2)]
    assert all(c["requests_per_second"] > 0 for c in figures["clients"])  # the clients drove
    assert figures["idle_scenes"]["scene_start_cpu_ms"]["count"] == 3  # a fresh scene each
    busy = figures["busy_connect"]
    assert busy["scenes"] == 2 and busy["connect_fresh_s"]["count"] == 5
    chaos = figures["chaos"]
    assert chaos["faults"] == 10 and set(chaos["by_kind"].values()) == {1}
    assert set(chaos["lost_by_kind"].values()) == {0} and "pile" in chaos["gap_ms"]
    assert chaos["acknowledged"] > 0 and chaos["lost"] == 0  # the journal's promise
    assert chaos["bystander_frames"] > 0
    on_cluster = figures["chaos_cluster"]
    assert on_cluster["by_kind"] == {"bus_kill": 1, "worker_kill": 1} and on_cluster["lost"] == 0
    assert on_cluster["acknowledged"] > 0 and on_cluster["read_answered_s"]["count"] > 0
    cluster = figures["cluster"]
    assert [(r["gateways"], r["viewers"]) for r in cluster["viewers"]["rows"]] == [(1, 2), (2, 2)]
    assert all(r["fps_median"] > 0 for r in cluster["viewers"]["rows"])  # frames crossed the bus
    assert cluster["busy"]["placed"] == 2 and cluster["failover"]["lost"] == 0
    tasks = figures["tasks"]  # a grasp trial (a row of one) and a second of Box and Blocks
    assert tasks["grasp"]["cpu_s"] > 0 and tasks["box_and_blocks"]["blocks"] == 20
    assert tasks["grasp_batch"] == tasks["grasp"] and tasks["grasp"]["trials"] == 1
    assert tasks["box_and_blocks"]["scene_s"] == 3.0
    learning = figures["gym"]  # six steps of one environment and of two, two resets
    assert learning["steps_per_s"] > 0 and learning["vector2_steps_per_s"] > 0
    assert 0 < learning["reset_ms"] <= learning["reset_ms_max"] and learning["step_overhead"] > 0
    markdown = (tmp_path / "RESULTS.md").read_text()
    assert markdown.count(BEGIN) == 1 and markdown.count(END) == 1
    for name in TARGETS:
        assert f"`{name}`" in markdown
    assert "each after 16.7 ms idle" in markdown and "after a period's idle" in markdown
