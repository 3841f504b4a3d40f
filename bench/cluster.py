"""The cluster under load (issue 29), on this machine and loopback only: a NATS bus, two
workers and one or two gateways, every process on the same two cores as the clients.

- **Viewers:** hands-10 driven at 60 Hz through the first gateway; light viewers (one
  asyncio process per gateway, :mod:`bench.viewers`) spread over the gateways; per count,
  frames per second, late frames and the CPU of the gateways, the worker and the bus. The
  most viewers held at ≤ 1 % late, with one gateway and with two.
- **Busy scenes:** scenes each with a hand whose fingers a client moves 10 times a second,
  opened through the gateways: how they spread over the workers, how long placing them
  took, the ticks a second they keep.
- **Failover:** a scene with kept objects (acknowledged, so journaled), its worker killed
  with SIGKILL: the time until the scene answers again through a gateway from another
  worker, and the objects lost.
"""

from __future__ import annotations

import asyncio
import json
import subprocess
import sys
import tempfile
import time
from contextlib import ExitStack, contextmanager
from dataclasses import asdict
from pathlib import Path
from typing import Any, Iterator

import virtual_prosthetics as vp

from tests.conftest import RunningServer
from server.cluster.leases import lease_holder
from server.cluster.roles import LEASE_SECONDS
from tests.server.cluster.conftest import Cluster, ask_bus, holder, running_bus

from .live import NICE, cpu_by_process, cpu_since, driving
from .processes import descendants
from .report import AT_60_HZ
from .stats import figure
from .viewers import run_viewers, sleep_until

ROOT = Path(__file__).resolve().parents[1]
LIMITS = ("--limit", "bytesPerSecond=1000000000", "--limit", "connectionsPerAddress=5000",
          "--limit", "connections=5000", "--limit", "sceneIdleSeconds=5")
LATE_PCT = 1.0
# of the machine's two cores, what each worker's scenes may use: the rest runs the gateways,
# the bus and the clients (with 1 each, the scenes measured as fitting got less than they
# wanted and ticked at 37/s)
WORKER_CORES = 0.7
QUIET_CORES = 0.25  # the cluster's CPU between two rows, once the last row's work is done


class LoadCluster(Cluster):
    """The tests' cluster with the bench's limits, two workers whose scenes may use
    ``WORKER_CORES`` each, and the bus's process (its CPU counts)."""

    def __init__(self, folder: Path, url: str, gateways: int, bus_pid: int) -> None:
        super().__init__(url, folder, *LIMITS, gateways=gateways,
                         worker_extra=("--worker-cores", str(WORKER_CORES)))
        self.folder, self.bus_pid = folder, bus_pid

    def pids(self) -> dict[str, list[int]]:
        """The processes of each role: the gateways'; the workers' and their scenes'; the bus's."""
        gateways = [g.process.pid for g in self.gateways]
        workers = [w.pid for w in self.workers.values()]
        return {"gateways": gateways + descendants(*gateways),
                "workers": workers + descendants(*workers), "bus": [self.bus_pid]}

    def seconds(self) -> dict[str, dict[int, float]]:
        """Each role's processes' CPU seconds so far."""
        return {role: cpu_by_process(pids) for role, pids in self.pids().items()}

    def cores_since(self, before: dict[str, dict[int, float]], started: float) -> dict[str, float]:
        """The cores each role used since ``before`` (taken at ``started``; :func:`cpu_since`)."""
        span = time.monotonic() - started
        return {role: cpu_since(before.get(role, {}), now) / span
                for role, now in self.seconds().items()}


@contextmanager
def load_cluster(gateways: int) -> Iterator[LoadCluster]:
    # (a killed process's last files may still be going as the folder goes: no reason to
    # lose the run's figures)
    with tempfile.TemporaryDirectory(prefix="vp-cluster-", ignore_cleanup_errors=True) as name, \
            ExitStack() as stack:
        folder = Path(name)
        url = stack.enter_context(running_bus(folder))
        # the buckets made first, with the product's lease (the tests' helpers, which the
        # bench shares, would make them with their short one)
        ask_bus(url, lambda bus: asyncio.sleep(0), lease_seconds=LEASE_SECONDS)
        bus_pid = int(subprocess.run(["pgrep", "-f", str(folder / "nats.conf")],
                                     capture_output=True, text=True).stdout.split()[0])
        running = LoadCluster(folder, url, gateways, bus_pid)
        try:
            yield running
        finally:
            running.close()


def measure(counts: list[int], seconds: float, busy: int, objects: int,
            idle_wait: float) -> dict[str, Any]:
    """Every measure on one cluster (two workers, two gateways): viewers through one gateway
    and through both; ``idle_wait`` later (their scene gone) the failover, which kills a
    worker; then, a new worker in its place, the busy scenes (last: past the cores they
    leave the cluster swamped)."""
    with load_cluster(2) as cluster:
        found = {"viewers": viewers(cluster, counts, seconds)}
        time.sleep(idle_wait)  # the viewed scenes gone
        found["failover"] = failover(cluster, objects)
        cluster.add_worker("wc")  # in place of the one killed
        found["busy"] = busy_scenes(cluster, busy, max(seconds, 5.0))
    return found


def headline(found: dict[str, Any]) -> dict[str, Any]:
    """The cluster's named figures of results.json."""
    rows = found["viewers"]["rows"]
    most = max(r["viewers"] for r in rows)
    busy = found["busy"]
    return {
        "cluster_viewers2000_late_pct": next(r["late_pct"] for r in rows
                                             if r["gateways"] == 2 and r["viewers"] == most),
        "cluster_gateway_scaling": found["viewers"]["scaling"],
        "cluster_busy_scenes_placed": busy["placed"],
        # (None when no busy scene answered: not a scene that ticked 0 times a second)
        "cluster_busy_scenes_fps_median": (busy["ticks_per_second"] or {}).get("median"),
        "cluster_failover_s": found["failover"]["seconds"] or float("inf"),
        "cluster_failover_lost": found["failover"]["lost"],
    }


def viewers(cluster: LoadCluster, counts: list[int], seconds: float) -> dict[str, Any]:
    """hands-10 driven at 60 Hz through the first gateway; per viewer count, viewers on the
    first gateway alone, then spread over both: their frames and the cluster's CPU; the
    most viewers held at ≤ 1 % late each way.

    Each row has a scene and a driver of its own: a gateway swamped by one row's viewers
    may drop that row's driver (its pongs too late), which must not leave the next rows
    with a scene standing still."""
    rows = []
    for gateways in (1, 2):
        for count in counts:
            scene = f"viewed{len(rows)}"
            _quiet(cluster)
            # (the driver at the servers' priority: it is the watched scene's source, and
            # the viewers' processes, at a lower one, must not starve it)
            with driving(cluster.gateways[0], scene, "hands", 10, 3600, nice=()) as driver:
                row = _viewer_run(cluster, cluster.gateways[:gateways], scene, count, seconds)
                lasted = driver.poll() is None
            rows.append({"gateways": gateways, **row, "driver_lasted": lasted})
    held = {g: max([r["viewers"] for r in rows if r["gateways"] == g and _held(r)], default=0)
            for g in (1, 2)}
    return {"rows": rows, "held": held, "scaling": held[2] / held[1] if held[1] else 0.0}


def _quiet(cluster: LoadCluster, most: float = 120.0) -> None:
    """Wait until the cluster is done with the last row (its gateways still writing to
    sockets whose viewers have gone, its scene running until idle), at most ``most`` s:
    a row started while the last one's work goes on measures both."""
    deadline = time.monotonic() + most
    while time.monotonic() < deadline:
        before, started = cluster.seconds(), time.monotonic()
        time.sleep(1.0)
        if sum(cluster.cores_since(before, started).values()) < QUIET_CORES:
            return


def _held(row: dict[str, Any]) -> bool:
    """Every viewer kept 60 Hz with at most 1 % of its frames late (a viewer that got no
    frame at all, its driver gone, holds nothing)."""
    return row["fps_min"] >= AT_60_HZ and row["late_pct"] <= LATE_PCT


def _viewer_run(cluster: LoadCluster, gateways: list[RunningServer], scene: str, count: int,
                seconds: float) -> dict[str, Any]:
    shares = [count // len(gateways) + (k < count % len(gateways)) for k in range(len(gateways))]
    commands = [[*NICE, sys.executable, "-m", "bench.viewers", gateway.ws, scene, str(share)]
                for gateway, share in zip(gateways, shares) if share]

    def cluster_cores(start: float, end: float) -> dict[str, float]:
        sleep_until(start)
        before = cluster.seconds()
        sleep_until(end)
        return cluster.cores_since(before, start)

    outputs, cores = run_viewers(commands, seconds, cluster_cores)
    found = [v for out in outputs for v in out["viewers"]]
    frames = sum(v["frames"] for v in found)
    fps = [v["fps"] for v in found]
    starved = sum(1 for v in found if v["frames"] == 0)  # every one of its frames missing
    return {"viewers": count, "fps_min": min(fps), "fps_median": figure(fps).median,
            "late_pct": 100.0 if starved else 100 * sum(v["late"] for v in found) / max(1, frames),
            # in the window: the cluster's roles; the viewers' processes over their whole run
            "cores": cores, "viewers_cpu_seconds": sum(out["cpu_seconds"] for out in outputs),
            # a gateway's CPU per frame sent to one viewer
            "gateway_us_per_viewer_frame": 1e6 * cores["gateways"] * seconds / max(1, frames)}


def busy_scenes(cluster: LoadCluster, count: int, seconds: float) -> dict[str, Any]:
    """``count`` scenes with a hand each, fingers moved 10 times a second by one client
    process, a refused scene asked for again every few seconds for a minute: how many the
    workers took, their spread, the time until every scene was placed or given up, their
    tick rate."""
    started = time.monotonic()
    driver = subprocess.Popen([*NICE, sys.executable, "-m", "bench.cluster_busy",
                               *[g.ws for g in cluster.gateways], str(count), str(seconds)],
                              cwd=ROOT, stdout=subprocess.PIPE, text=True)
    assert driver.stdout is not None
    placed = json.loads(driver.stdout.readline())
    placing = time.monotonic() - started
    time.sleep(seconds * 0.2)
    cpu_before, measured = cluster.seconds(), time.monotonic()
    time.sleep(seconds * 0.5)
    cores = cluster.cores_since(cpu_before, measured)
    metrics = {name: m for gateway in cluster.gateways
               for name, m in gateway.get("/api/metrics")["scenes"].items()}
    busy = [m for name, m in metrics.items() if name.startswith("busy")]
    # A scene whose process did not answer within the gateway's second has no figures of its
    # own in its entry: it is counted as unanswered, not as a scene that ticks 0 times a second.
    rates = [m["ticksPerSecond"] for m in busy if "ticksPerSecond" in m]
    spread = ask_bus(cluster.url, lambda bus: _holders(bus, count))
    driver.communicate(timeout=seconds + 120)
    return {"scenes": count, "placed": placed["placed"], "refused": placed["failed"],
            "placing_s": placing,
            "per_worker": spread, "cores": cores,
            "ticks_per_second": asdict(figure(rates)) if rates else None,
            "unanswered": len(busy) - len(rates)}


async def _holders(bus: Any, count: int) -> dict[str, int]:
    spread: dict[str, int] = {}
    for k in range(count):
        worker = await lease_holder(bus.workers, bus.scenes, f"busy{k}") or "none"
        spread[worker] = spread.get(worker, 0) + 1
    return spread


def failover(cluster: LoadCluster, objects: int) -> dict[str, Any]:
    """A scene with ``objects`` kept boxes; its worker killed: seconds until the scene
    answers again through a gateway with them, and the objects lost."""
    gateway = cluster.gateways[1]
    with vp.connect(cluster.gateways[0].ws, scene="failover", keep=True) as session:
        boxes = [vp.Box(0.2, 0.2, 0.2) for _ in range(objects)]
        for k, box in enumerate(boxes):
            box.set_position(k % 10, 0.1, k // 10)
        session.sync()  # acknowledged: journaled
    first = holder(cluster.url, "failover")
    assert first is not None
    killed = time.monotonic()
    cluster.kill_worker(first)
    found = None
    while time.monotonic() - killed < 60:
        try:
            nodes = gateway.get("/api/scenes/failover/snapshot")["nodes"]
        except Exception:  # the scene has failed, and is not placed again yet
            nodes = None
        if nodes is not None and holder(cluster.url, "failover") not in (None, first):
            found = nodes
            break
        _reopen(gateway)
        time.sleep(0.05)
    back = time.monotonic() - killed
    ids = {box.id for box in boxes}
    return {"objects": objects, "seconds": back if found is not None else None,
            "lost": len(ids - {n["id"] for n in found or []})}


def _reopen(gateway: RunningServer) -> None:
    """What a client coming back does: connect (the scene starts again on a worker)."""
    try:
        with vp.connect(gateway.ws, scene="failover", role="viewer"):
            pass
    except Exception:  # not yet placed: the next round tries again
        pass


if __name__ == "__main__":  # python -m bench.cluster VIEWERS[,VIEWERS…] BUSY_SCENES
    print(json.dumps(measure([int(c) for c in sys.argv[1].split(",")], 5.0, int(sys.argv[2]),
                             50, 20.0), indent=1, default=str))
