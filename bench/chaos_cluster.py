"""The chaos run on a cluster: the bus and the workers fail (issue 44, G5, G16).

A bus (nats-server), two workers and a gateway share one state folder. The changer of
:mod:`.chaos` changes scene WORK through the gateway as fast as its answers come; a
bystander watches scene BYSTANDER through it too. Faults, in turn: ``kill -9`` of the bus
(started again BUS_DOWN_SECONDS later, on the same port and store) and ``kill -9`` of the
worker running WORK with its scenes' processes (nothing saved on the way; a fresh worker
takes its place). After each, every change the gateway acknowledged is looked for in
WORK, read through the gateway. Also measured: how long a REST read waited for its answer
while the bus was away (it must be an answer: 503 ``bus_unavailable``), and how long after
each fault WORK answered again.
"""

from __future__ import annotations

import itertools
import json
import tempfile
import time
import urllib.error
import urllib.request
from pathlib import Path
from typing import Any

from tests.server.cluster.conftest import BusServer, Cluster, holder

from .chaos import BYSTANDER, WORK, Changer, Ledger, bystanding, summary
from .stats import figure

KINDS = ("bus_kill", "worker_kill")
BUS_DOWN_SECONDS = 5.0  # (a quick run: 1.5 s; reads are refused from the first moment)


class ClusterChaos:
    """The cluster, its changer and the faults."""

    def __init__(self, folder: Path, seed: int, bus_down: float) -> None:
        self.bus_down = bus_down
        self.bus = BusServer(folder)
        self.bus.start()
        self.cluster = Cluster(self.bus.url, folder, gateways=1)
        self.gateway = self.cluster.gateways[0]
        self.ledger = Ledger()
        self.changer = Changer(lambda: self.gateway.ws, self.ledger, seed)
        self.windows: list[tuple[str, float, float]] = []
        self.checks: list[dict[str, Any]] = []
        self.answered: list[float] = []  # a read's wait while the bus was away, s
        self.back: dict[str, list[float]] = {kind: [] for kind in KINDS}
        self._names = itertools.count(1)

    def bus_kill(self) -> None:
        self.bus.kill()
        started = time.monotonic()
        while time.monotonic() - started < self.bus_down:
            asked = time.monotonic()
            status = _status(f"{self.gateway.http}/api/scenes/{WORK}/robots")
            if status == 503:
                self.answered.append(time.monotonic() - asked)
            time.sleep(0.25)
        self.bus.start()

    def worker_kill(self) -> None:
        running = holder(self.bus.url, WORK)
        if running is not None:
            self.cluster.kill_worker(running)
        self.cluster.add_worker(f"w{next(self._names)}")

    def fault(self, kind: str) -> None:
        """Inject one fault while the changer runs, then check every acknowledged change."""
        self.changer.running.set()
        time.sleep(0.5)
        started = time.monotonic()
        getattr(self, kind)()
        ended = time.monotonic()
        nodes = self._nodes()
        self.back[kind].append(time.monotonic() - ended)
        self.windows.append((kind, started, time.monotonic()))
        time.sleep(0.5)
        self.changer.running.clear()
        self.changer.idle.wait(60)
        lost = self.ledger.lost_in(self._nodes() or nodes)
        self.checks.append({"kind": kind, "lost": lost, "acknowledged": self.ledger.acknowledged})

    def _nodes(self) -> list[dict[str, Any]]:
        """WORK's nodes through the gateway, once it answers again."""
        deadline = time.monotonic() + 60
        while True:
            try:
                return self.gateway.get(f"/api/scenes/{WORK}/snapshot")["nodes"]  # type: ignore[no-any-return]
            except (OSError, urllib.error.HTTPError):
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.1)

    def watched(self) -> None:
        """Return once the bystander's scene runs and has had a second of frames."""
        deadline = time.monotonic() + 60
        while _status(f"{self.gateway.http}/api/scenes/{BYSTANDER}/snapshot") != 200:
            if time.monotonic() > deadline:
                raise TimeoutError("the bystander's scene did not start")
            time.sleep(0.1)
        time.sleep(1.0)

    def close(self) -> None:
        self.changer.stopped = True
        self.cluster.close()
        self.bus.stop()


def _status(url: str) -> int:
    try:
        with urllib.request.urlopen(url, timeout=60) as answer:
            return int(answer.status)
    except urllib.error.HTTPError as error:
        return error.code


def run(faults: int, seed: int = 1, quick: bool = False) -> dict[str, Any]:
    """``faults`` faults, the kinds in turn: what was acknowledged, lost and seen."""
    with tempfile.TemporaryDirectory(prefix="vp-chaos-cluster-") as folder:
        chaos = ClusterChaos(Path(folder), seed, 1.5 if quick else BUS_DOWN_SECONDS)
        started = time.monotonic()
        try:
            with bystanding(chaos.gateway.ws) as frames:
                chaos.changer.start()
                chaos.changer.running.set()
                chaos._nodes()  # (WORK placed and changed before the first fault)
                chaos.watched()
                for k in range(faults):
                    chaos.fault(KINDS[k % len(KINDS)])
        finally:
            chaos.close()
        found = summary(chaos, frames, time.monotonic() - started, KINDS, KINDS)
        found["bus_down_s"] = chaos.bus_down
        found["read_answered_s"] = figure(chaos.answered)
        found["read_answered_worst_s"] = max(chaos.answered, default=float("inf"))
        found["back_s"] = {kind: figure(values) for kind, values in chaos.back.items() if values}
        found["back_worst_s"] = {kind: max(values) for kind, values in chaos.back.items() if values}
        return found


if __name__ == "__main__":
    import sys
    print(json.dumps(run(int(sys.argv[1]) if len(sys.argv) > 1 else len(KINDS)),
                     default=lambda f: f.as_dict(), indent=1))
