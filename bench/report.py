"""RESULTS.md's generated section: the machine, the run, every figure with its reference
and its target (one table of targets, here)."""

from __future__ import annotations

import os
import platform
import re
import time
from importlib.metadata import version
from pathlib import Path
from typing import Any, Callable

BEGIN = "<!-- bench:begin: written by `make bench` (bench/run.py); notes go below the end mark -->"
END = "<!-- bench:end -->"
PERIOD_MS = 1000 / 60
AT_60_HZ = 59.0  # ticks or frames per second that count as keeping 60 Hz (rounding)

# headline name → (target as written, test)
TARGETS: dict[str, tuple[str, Callable[[float], bool]]] = {
    "tick_ratio_hands10": ("≤ 1.2× the floor", lambda v: v <= 1.2),
    "tick_ratio_hands50": ("≤ 1.2× the floor", lambda v: v <= 1.2),
    "sensors100_ms": ("≤ 0.5 ms", lambda v: v <= 0.5),
    "sensors100_ratio": ("≤ 2× one rayTestBatch of the same rays", lambda v: v <= 2),
    "requests_per_s": ("≥ 20 000 /s", lambda v: v >= 20_000),
    "latency_p99_ms": ("p99 ≤ 2 tick periods (33.3 ms)", lambda v: v <= 2 * PERIOD_MS),
    "viewers1000_fps_min": ("60 Hz", lambda v: v >= AT_60_HZ),
    "viewers1000_late_pct": ("≤ 1 %", lambda v: v <= 1),
    "viewer_frame_us": ("≤ 4 µs of the web process per frame per viewer", lambda v: v <= 4),
    "client_cpu_hands10_pct": ("≤ 25 % of a core (hands-10 through the Python client's vp.run)",
                               lambda v: v <= 25),
    "client_cpu_hands10_js_pct": ("≤ 25 % of a core (hands-10 through the JS client in Node)",
                                  lambda v: v <= 25),
    "frame_bytes_two_hands": ("≤ 1 KB (1024 B)", lambda v: v <= 1024),
    "max_hands_60hz": ("≥ 100", lambda v: v >= 100),
    "dynamic_hands10_objects50_tick_ms": ("≤ 12 ms (headroom in a 16.7 ms tick period)",
                                          lambda v: v <= 12),
    "server_cpu_hands10_pct": ("≤ 25 % of a core", lambda v: v <= 25),
    "hands100_outside_ticks_per_s": ("100 hands driven from outside hold 60 Hz", lambda v: v >= AT_60_HZ),
    "two_scenes_fps_min": ("both at 60 Hz", lambda v: v >= AT_60_HZ),
    "busy_server_connect_s": ("a script connects to a server busy with 13 animated scenes within "
                              "10 s (p95; the clients' old fixed wait; 60 s by default now)",
                              lambda v: v <= 10),
    "idle_scenes_server_cpu_pct": ("idle scenes cost memory only (≤ 1 % of a core)", lambda v: v <= 1),
    "idle_scene_mb": ("≤ 70 MB (scene_capacity.SCENE_BYTES)", lambda v: v <= 70),
    "pile2000_tick_ms_max": ("no tick > 250 ms (2 000 balls made in one spot)", lambda v: v <= 250),
    "pile2000_ticks_per_s_after_5s": ("≥ 10 ticks/s from 5 s after the burst", lambda v: v >= 10),
    "pile2000_ticks_per_s_settled": ("back to 60 once settled", lambda v: v >= AT_60_HZ),
    "pile2000_viewer_fps_min": ("viewers get ≥ 4 frames every second", lambda v: v >= 4),
    "tower300_tick_ms_max": ("no tick > 250 ms (a tower of 300 boxes)", lambda v: v <= 250),
    "chaos_faults": ("≥ 200 faults injected", lambda v: v >= 200),
    "chaos_changes_lost": ("0 acknowledged changes lost", lambda v: v == 0),
    "chaos_bystander_gap_ms": ("< 100 ms between frames", lambda v: v < 100),
    "cluster_chaos_changes_lost": ("0 acknowledged changes lost to bus and worker kills",
                                   lambda v: v == 0),
    "bus_away_read_answered_s": ("a read answered within 10 s with the bus away (503)",
                                 lambda v: v <= 10),
    "recording_seek_ms_max": ("< 200 ms, any time of 10 minutes of 10 hands", lambda v: v < 200),
    "cluster_viewers2000_late_pct": ("≤ 1 % (2 000 viewers over two gateways)", lambda v: v <= 1),
    "cluster_gateway_scaling": ("≥ 1.8 (viewers held at ≤ 1 % late, two gateways over one)",
                                lambda v: v >= 1.8),
    "cluster_busy_scenes_placed": ("200 busy scenes placed over two workers", lambda v: v >= 200),
    "cluster_busy_scenes_fps_median": ("60 Hz", lambda v: v >= AT_60_HZ),
    "cluster_failover_s": ("a killed worker's scene back within the lease (10 s)", lambda v: v <= 10),
    "cluster_failover_lost": ("0 saved objects lost", lambda v: v == 0),
    "grasp_trial_realtime_x": ("≥ 3× real time on one core", lambda v: v >= 3),
    "grasp_batch_trial_realtime_x": ("≥ 3× real time on one core, a trial of ten side by side",
                                     lambda v: v >= 3),
    "bb_cpu_per_scene_s": ("≤ 0.5 CPU-s per scene-s", lambda v: v <= 0.5),
    "gym_steps_per_s": ("≥ 60 (a step is a tick: faster than real time)", lambda v: v >= 60),
    "gym_vector2_speedup": ("≥ 1.7 (two scenes over one, on 2 cores)", lambda v: v >= 1.7),
    "gym_reset_ms": ("≤ 50 ms", lambda v: v <= 50),
    "gym_step_overhead": ("≤ 1.5 (a step through the server over the same tick in-process)",
                          lambda v: v <= 1.5),
}


def write(path: Path, body: list[str]) -> None:
    """Put the generated section (``body``'s lines between the marks) at the top of
    ``path``, in place of the last one; whatever follows its end mark stays."""
    section = "\n".join([BEGIN, *body, END])
    old = path.read_text() if path.exists() else "# Benchmark results\n\n"
    if BEGIN in old and END in old:
        new = old[:old.index(BEGIN)] + section + old[old.index(END) + len(END):]
    else:
        title, _, rest = old.partition("\n")
        new = f"{title}\n\n{section}\n{rest}"
    path.write_text(new)


def machine() -> str:
    """CPU model, cores, memory, Python and PyBullet versions."""
    cpu = re.search(r"model name\s*:\s*(.*)", Path("/proc/cpuinfo").read_text())
    memory = re.search(r"MemTotal:\s*(\d+)", Path("/proc/meminfo").read_text())
    gib = int(memory.group(1)) / 2**20 if memory else 0
    return (f"{cpu.group(1) if cpu else platform.processor()}, {os.cpu_count()} cores, "
            f"{gib:.0f} GiB; Python {platform.python_version()}, PyBullet "
            f"{version('pybullet')}, numpy {version('numpy')}")


def lines(results: dict[str, Any], found: dict[str, Any]) -> list[str]:
    """The section's lines: machine, run, the headline figures, every measure, viewers."""
    run = "quick run (tiny scenes: the figures mean nothing)" if results["quick"] else "full run"
    out = ["", f"## Latest run: {time.strftime('%Y-%m-%d %H:%M %Z')}", "",
           f"Machine: {machine()}.  ",
           f"Commit `{results['commit']}`, {run}, {results['seconds']} s. Everything ran on "
           "this one machine; clients (drivers, viewers) in processes of their own at nice 10.",
           "", *headline_table(results), "", *figure_table(found), "",
           *viewer_table(found["viewers"], found["fanout_floor"]), "", *piles_table(found["piles"]), "",
           *chaos_table(found["chaos"]), "",
           *cluster_chaos_table(found["chaos_cluster"]), "",
           *cluster_table(found["cluster"]), ""]
    return out


def headline_table(results: dict[str, Any]) -> list[str]:
    rows = ["| results.json | value | target | met |", "|---|---|---|---|"]
    for name, (target, test) in TARGETS.items():
        value = results[name]
        if value is None:  # not measured in this run (the note below its table says why)
            rows.append(f"| `{name}` | none | {target} | **no** |")
            continue
        rows.append(f"| `{name}` | {_number(value)} | {target} | {'yes' if test(value) else '**no**'} |")
    return rows


def figure_table(found: dict[str, Any]) -> list[str]:
    rows = ["| measure | median | p95 | reference, same run (median) | ours / reference |",
            "|---|---|---|---|---|"]
    rows += tick_rows(found) + outside_rows(found)
    for m in found["sensors"]:
        rows.append(f"| sensing step, {m['sensors']} watched sensors (frame {m['frame_bytes'].median:.0f} B) "
                    f"| {_ms(m['sensing_ms'].median)} | {_ms(m['sensing_ms'].p95)} | one `rayTestBatch`: "
                    f"{_ms(m['floor_ms'].median)} | {m['ratio']:.2f}× |")
    r = found["requests"]
    rows.append(f"| `setAngles` (20 angles) through a session | {r['per_second']:,.0f} /s | | "
                f"`json.loads` + `json.dumps` of the same texts: {r['json_only_per_second']:,.0f} /s "
                f"| {r['ratio']:.2f}× |")
    lat = found["latency"]
    rows.append(f"| `setAngle` → another client's frame ({lat['rounds']} changes; p99 "
                f"{_ms(lat['p99_ms'])}) | {_ms(lat['ms'].median)} | {_ms(lat['ms'].p95)} | one tick "
                f"period: {_ms(PERIOD_MS)} | p99 {lat['p99_in_periods']:.2f} periods |")
    f = found["frames"]["frame_bytes"]
    rows.append(f"| frame of two hands moving all 40 motors | {f.median:.0f} B | {f.p95:.0f} B | 1 KB | "
                f"{f.median / 1024:.2f}× |")
    for row in found["max_hands"]["rows"]:
        rows.append(f"| applying a step and ticking hands-{row['hands']} | {_ms(row['step_ms'].median)} "
                    f"| {_ms(row['step_ms'].p95)} | one tick period: {_ms(PERIOD_MS)} | "
                    f"{row['step_ms'].median / PERIOD_MS:.2f}× |")
    dyn = found["dynamic"]
    for label, key in (("falling (the first ticks after they are dropped)", "falling_ms"),
                       ("lying on the ground", "tick_ms")):
        rows.append(f"| dynamic mode: a tick of {dyn['hands']} hands flexing and {dyn['objects']} objects "
                    f"{label}, 5 substeps | {_ms(dyn[key].median)} | {_ms(dyn[key].p95)} | "
                    f"one tick period: {_ms(PERIOD_MS)} | {dyn[key].median / PERIOD_MS:.2f}× |")
    rows.append(f"| of which Bullet's own steps (`stepSimulation`, 5 a tick at these physics settings: "
                f"the tick's floor) | {_ms(dyn['stepping_ms'].median)} | {_ms(dyn['stepping_ms'].p95)} | "
                f"the tick: {_ms(dyn['tick_ms'].median)} | "
                f"{dyn['tick_ms'].median / dyn['stepping_ms'].median:.2f}× |")
    rec = found["recording"]
    rows.append(f"| recording hands-{rec['hands']} with every motor turning every tick: the recorder's time "
                f"a tick (its MCAP file: {rec['mb_per_minute']:.1f} MB a minute) | {_ms(rec['record_ms'].median)} | "
                f"{_ms(rec['record_ms'].p95)} | one tick period: {_ms(PERIOD_MS)} | "
                f"{rec['record_ms'].median / PERIOD_MS:.2f}× |")
    rows.append(f"| seeking to a random time of that recording ({rec['minutes']:.1f} min, "
                f"{rec['bytes'] / 1e6:.0f} MB): the scene then, as a player gets it | "
                f"{_ms(rec['seek_ms'].median)} | {_ms(rec['seek_ms'].p95)} | 200 ms | "
                f"{rec['seek_ms'].median / 200:.2f}× |")
    two = found["two_scenes"]
    rows.append(f"| two scenes of hands-{two['hands']} driven at once: ticks/s | "
                f"{' and '.join(f'{t:.1f}' for t in two['ticks_per_second'])} | tick p95 "
                f"{' and '.join(_ms(t) for t in two['tick_ms_p95'])} | 60 Hz | |")
    busy = found["busy_connect"]
    rows.append(f"| a script's `vp.connect` to a fresh scene / to a busy one, while {busy['scenes']} "
                f"scenes of hands-{busy['hands']} are animated at 60 Hz | "
                f"{busy['connect_fresh_s'].median:.2f} s / {busy['connect_busy_s'].median:.2f} s | "
                f"{busy['connect_fresh_s'].p95:.2f} s / {busy['connect_busy_s'].p95:.2f} s | "
                f"the clients wait 60 s (10 s before) | |")
    idle = found["idle_scenes"]
    rows.append(f"| {idle['scenes']} idle scenes (opened and left): a new client's `hello`, fresh scene "
                f"/ idle scene; whole server {idle['server_cpu_pct']:.1f} % of a core | "
                f"{_ms(idle['hello_new_scene_ms'].median)} / {_ms(idle['hello_idle_scene_ms'].median)} | "
                f"{_ms(idle['hello_new_scene_ms'].p95)} / {_ms(idle['hello_idle_scene_ms'].p95)} | "
                f"memory of a scene's process (PSS): {idle['scene_pss_mb'].median:.0f} MB, all "
                f"{idle['scenes_pss_mb'] / 1024:.1f} GB; a fresh scene's process took "
                f"{_ms(idle['scene_start_cpu_ms'].median)} of CPU to start | |")
    return rows


def tick_rows(found: dict[str, Any]) -> list[str]:
    """In-process ticks and steps against bare PyBullet's (back to back, then after idle)."""
    rows = []
    for key in ("hands10", "hands50", "arms11"):
        m, label = found[key], found[key]["scene"]
        rows.append(f"| tick of {label} ({m['bodies']} bodies), in-process | {_ms(m['tick_ms'].median)} "
                    f"| {_ms(m['tick_ms'].p95)} | bare PyBullet: {_ms(m['floor_ms'].median)} "
                    f"(p95 {_ms(m['floor_ms'].p95)}) | {m['ratio']:.2f}× |")
        rows.append(f"| applying one step of {label} through a session (decode, check, apply; "
                    f"not in the tick) | {_ms(m['apply_ms'].median)} "
                    f"| {_ms(m['apply_ms'].p95)} | | |")
    m = found["hands10_idle"]
    rows.append(f"| tick of {m['scene']}, in-process, each after {1000 * m['idle_s']:.1f} ms idle "
                f"(as a 60 Hz server's ticks start) | {_ms(m['tick_ms'].median)} | {_ms(m['tick_ms'].p95)} "
                f"| bare PyBullet after the same idle: {_ms(m['floor_ms'].median)} | {m['ratio']:.2f}× |")
    return rows


def outside_rows(found: dict[str, Any]) -> list[str]:
    """Ticks through a server driven from outside, against bare PyBullet's in-process."""
    rows, idle_floor = [], found["hands10_idle"]["floor_ms"].median
    for row, key in zip(found["outside"], ("hands10", "hands50", None)):
        floor = found[key]["floor_ms"].median if key else None
        if key == "hands10":  # its ticks start after a period's idle, as the idle row's
            reference = (f"bare PyBullet: {_ms(floor)}; after a period's idle {_ms(idle_floor)} "
                         f"| {row['tick_ms_p50'] / floor:.2f}× ({row['tick_ms_p50'] / idle_floor:.2f}×)")
        elif floor:
            reference = f"bare PyBullet: {_ms(floor)} | {row['tick_ms_p50'] / floor:.2f}×"
        else:
            reference = f"60 ticks/s | {row['ticks_per_second'] / 60:.2f}×"
        rows.append(f"| tick of hands-{row['hands']} from outside, driven at 60 Hz (/api/metrics; "
                    f"{row['ticks_per_second']:.1f} ticks/s, scene process {row['cpu_percent']:.0f} % CPU; "
                    f"whole server {100 * row['server_cores']:.0f} % of a core, "
                    f"{100 * row['server_cores'] / row['hands']:.1f} % a hand) "
                    f"| {_ms(row['tick_ms_p50'])} | {_ms(row['tick_ms_p95'])} | {reference} |")
    return rows


def viewer_table(rows: list[dict[str, Any]], floor_us: float) -> list[str]:
    out = ["Viewers on hands-10 driven at 60 Hz (light readers in one process; \"late\": more "
           "than two tick periods after the previous frame; \"skipped\": frames it never got, "
           "as a slow reader gets only the latest). The floor of a viewer-frame, one `send` "
           f"of the same bytes per loopback socket from a bare loop (bench/fanout_floor.py, as "
           f"many sockets as the most viewers): {floor_us:.1f} µs.", "",
           "| viewers | one more that never reads | frames/s lowest / median | late | skipped "
           "| server CPU (cores: web process + scene process) | fan-out µs a viewer-frame "
           "(in the web process) | driver lasted |", "|---|---|---|---|---|---|---|---|"]
    for row in rows:
        out.append(f"| {row['viewers']} | {'yes' if row['stalled'] else 'no'} | "
                   f"{row['fps_min']:.1f} / {row['fps_median']:.1f} | {row['late_pct']:.2f} % | "
                   f"{row['skipped_pct']:.2f} % | {row['server_cores']:.2f} | "
                   f"{row['fanout_us_per_viewer_frame']:.1f} | "
                   f"{'yes' if row['driver_lasted'] else '**no**'} |")
    return out


def piles_table(found: dict[str, Any]) -> list[str]:
    """bench/piles.py: a dynamic scene given a pile in one batch, from the burst on."""
    out = ["Piles (bench/piles.py): a dynamic scene given, in one batch, balls of radius 0.2 "
           "made at one point, or boxes of 0.5 m stacked into a tower; the scene's figures "
           "(/api/metrics) every 0.5 s from the batch on, and a viewer's frames:", "",
           "| pile | batch answered | longest tick | ticks/s at 5-6 s / worst second after 5 s "
           "/ last 2 s | last frame that moved something | viewer's longest gap / fewest frames "
           "in a second | process memory, most |", "|---|---|---|---|---|---|---|"]
    for row in found.values():
        out.append(f"| {row['count']} {row['kind']} | {row['batch_answered_s']:.2f} s | "
                   f"{_ms(row['tick_ms_max'])} | {row['ticks_per_s_at_5s']:g} / "
                   f"{row['ticks_per_s_min_after_5s']:g} / {row['ticks_per_s_end']:g} | "
                   f"{row['settled_s']:g} s after the batch (watched {row['seconds']:g} s) | "
                   f"{_ms(row['viewer_gap_ms_max'])} / {row['viewer_fps_min']} | "
                   f"{row['rss_mb_max']} MB |")
    return out


def chaos_table(run: dict[str, Any]) -> list[str]:
    """The chaos run (bench/chaos.py): faults, changes, the bystander's worst gaps."""
    out = [f"Chaos run ({run['seconds']:.0f} s): a script changed one scene as fast as its "
           f"answers came while {run['faults']} faults were injected ({run['rounds']} rounds "
           f"of each kind); after each, every acknowledged change was looked for. "
           f"{run['acknowledged']:,} changes acknowledged, **{run['lost']} lost** "
           f"({run['uncertain']} left unanswered by a fault, not counted). A viewer of "
           f"another scene noted each frame; its longest gap during each kind of fault:", "",
           "| fault | injected | acknowledged changes lost after it | bystander's longest gap, "
           "median / worst |", "|---|---|---|---|"]
    for kind, count in run["by_kind"].items():
        gap = run["gap_ms"].get(kind)
        shown = f"{_ms(gap.median)} / {_ms(run['gap_worst_ms'][kind])}" if gap else \
            "(the server itself restarts: not a bystander's gap)"
        out.append(f"| {kind} | {count} | {run['lost_by_kind'][kind]} | {shown} |")
    return out


def cluster_chaos_table(run: dict[str, Any]) -> list[str]:
    """bench/chaos_cluster.py: bus kills and worker kills under a changing script."""
    out = [f"Chaos on a cluster ({run['seconds']:.0f} s; bench/chaos_cluster.py: a bus, two "
           f"workers and a gateway sharing a state folder): the same script changed a scene "
           f"through the gateway while the bus was killed -9 (back after {run['bus_down_s']:g} s) "
           f"or the worker running the scene was killed -9 with its scenes (a fresh one "
           f"started). {run['acknowledged']:,} changes acknowledged, **{run['lost']} lost** "
           f"({run['uncertain']} left unanswered by a fault). With the bus away a REST read of "
           f"the scene was answered (503 `bus_unavailable`) in "
           f"{_seconds(run['read_answered_s'], run['read_answered_worst_s'])} (median / worst). A viewer of another scene through the gateway "
           f"noted each frame (with the bus away it gets none: frames cross the bus):", "",
           "| fault | injected | acknowledged changes lost after it | the scene answered again "
           "after, median / worst | bystander's longest gap, median / worst |",
           "|---|---|---|---|---|"]
    for kind, count in run["by_kind"].items():
        gap, back = run["gap_ms"].get(kind), run["back_s"].get(kind)
        out.append(f"| {kind} | {count} | {run['lost_by_kind'][kind]} | "
                   f"{_seconds(back, run['back_worst_s'][kind]) if back else '-'} | "
                   f"{_ms(gap.median) + ' / ' + _ms(run['gap_worst_ms'][kind]) if gap else '-'} |")
    return out


def _seconds(values: Any, worst: float) -> str:
    return f"{values.median:.2f} s / {worst:.2f} s" if values.count else "-"


def cluster_table(found: dict[str, Any]) -> list[str]:
    """bench/cluster.py: viewers over one and two gateways, busy scenes, the failover."""
    out = ["Cluster (bench/cluster.py: a NATS bus, two workers, two gateways, all on this "
           "machine's cores with the clients): hands-10 driven at 60 Hz through the first "
           "gateway (a scene and a driver of its own for each row), light viewers on the first "
           "gateway alone or spread over both:", "",
           "| gateways | viewers | frames/s lowest / median | late | cores: gateways / workers and scenes / bus | gateway µs a viewer-frame | viewers' processes (CPU s) | driver lasted |",
           "|---|---|---|---|---|---|---|---|"]
    for row in found["viewers"]["rows"]:
        cores = row["cores"]
        out.append(f"| {row['gateways']} | {row['viewers']} | {row['fps_min']:.1f} / "
                   f"{row['fps_median']:.1f} | {row['late_pct']:.2f} % | {cores['gateways']:.2f} / "
                   f"{cores['workers']:.2f} / {cores['bus']:.2f} | "
                   f"{row['gateway_us_per_viewer_frame']:.1f} | {row['viewers_cpu_seconds']:.1f} | "
                   f"{'yes' if row['driver_lasted'] else '**no**'} |")
    busy, fail = found["busy"], found["failover"]
    rates = busy["ticks_per_second"]
    ticking = ("no scene answered /api/metrics within the gateway's second" if rates is None else
               f"ticks/s median {rates['median']:.1f} of the scenes that answered /api/metrics "
               f"within the gateway's second")
    out += ["", f"Busy scenes: {busy['scenes']} asked for (a hand each, its fingers moved 10 "
            f"times a second), {busy['placed']} placed ({', '.join(f'{w}: {n}' for w, n in sorted(busy['per_worker'].items()))}), "
            f"{busy['refused']} still refused after a minute of asking again every 3 s (the workers full), "
            f"all settled in {busy['placing_s']:.1f} s; "
            f"{ticking} ({busy.get('unanswered', 0)} did not); cluster CPU {sum(busy['cores'].values()):.2f} cores. "
            f"Failover: a scene with {fail['objects']} kept objects, its worker killed (SIGKILL): "
            f"back through the other gateway after "
            f"{'never' if fail['seconds'] is None else format(fail['seconds'], '.2f') + ' s'}, "
            f"{fail['lost']} objects lost."]
    return out


def _ms(value: float) -> str:
    return f"{value:.2f} ms" if value < 100 else f"{value:.0f} ms"


def _number(value: float) -> str:
    return f"{value:,.2f}" if isinstance(value, float) else f"{value:,}"
