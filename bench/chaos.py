"""The chaos run: a server with ``--state-dir`` under a script that keeps changing a scene,
while faults are injected one after another, and after each one every change the server
acknowledged is looked for.

Faults, in turn: ``kill -9`` of the whole server (then started again), a graceful restart,
``kill -9`` of the changed scene's process, ``SIGSTOP`` of it for a second, the scenes
folder made unwritable for 1.5 s, a 5 MB import into a third scene, a 7 MB upload, a
stranger's pile (1 000 balls made in one spot of a dynamic scene of its own, kept a second),
two clients exporting a RoundHand's URDF in a loop for 1.5 s, and a recording resimulated.
A bystander viewer of another scene (a process of its own) notes when each frame arrives;
the worst gap between two frames during each fault (the server's own restarts aside) is
what the bystander saw of it. Loopback only; everything stops when the run ends.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import random
import signal
import tempfile
import threading
import time
import urllib.error
import urllib.request
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator

import trimesh
from websockets.exceptions import ConnectionClosed, InvalidHandshake
from websockets.sync.client import connect

from server.core.protocol.operations import Operations
from server.core.scene.scene import Scene
from server.core.protocol.scene_document import encode_document, export_scene
from tests.conftest import RunningServer, crash_server, start_server, stop_server, unwritable

from .live import ask
from .piles import pile_batch
from .stats import figure

WORK, BYSTANDER, IMPORTS, EXPORTS = "work", "bystander", "imports", "exports"
KINDS = ("server_kill", "scene_kill", "scene_stop", "unwritable", "import", "upload",
         "restart", "pile", "export", "resimulate")
GAP_KINDS = ("scene_kill", "scene_stop", "unwritable", "import", "upload", "pile", "export",
             "resimulate")  # the server runs on


@dataclass
class Ledger:
    """What the server acknowledged: each object's last position (None once deleted);
    objects with a request lost in flight are uncertain and left out of the checks."""

    objects: dict[str, list[float] | None] = field(default_factory=dict)
    uncertain: set[str] = field(default_factory=set)
    acknowledged: int = 0

    def lost_in(self, nodes: list[dict[str, Any]]) -> list[str]:
        """The acknowledged states a scene's nodes do not show."""
        there = {n["id"]: n["position"] for n in nodes}
        lost = []
        for object_id, position in self.objects.items():
            if object_id in self.uncertain:
                continue
            if position is None and object_id in there or position is not None and (
                    object_id not in there or
                    any(abs(a - b) > 1e-9 for a, b in zip(there[object_id], position))):
                lost.append(object_id)
        return lost


class Changer(threading.Thread):
    """One script changing scene WORK as fast as its answers come, as the same client
    throughout (its resume key), its objects kept; it waits while told to pause."""

    def __init__(self, url: Callable[[], str], ledger: Ledger, seed: int) -> None:
        super().__init__(daemon=True)
        self.url, self.ledger, self.rng = url, ledger, random.Random(seed)
        self.resume: str | None = None
        self.client = ""
        self.running = threading.Event()
        self.idle = threading.Event()
        self.stopped = False
        self.next = 1

    def run(self) -> None:
        while not self.stopped:
            if not self.running.is_set():
                self.idle.set()
                self.running.wait(0.1)
                continue
            self.idle.clear()
            try:
                self._session()
            except (OSError, ConnectionClosed, InvalidHandshake, TimeoutError, ValueError):
                time.sleep(0.05)  # the server or the scene is going or coming back

    def _session(self) -> None:
        query = f"scene={WORK}&keep=true" + (f"&resume={self.resume}" if self.resume else "")
        with connect(f"{self.url()}/ws?{query}", open_timeout=5, max_size=None) as ws:
            hello = json.loads(ws.recv(timeout=10))
            if hello["op"] != "hello":
                raise ValueError(hello.get("message", "refused"))
            self.client, self.resume = hello["client"], hello["resume"]
            while self.running.is_set() and not self.stopped:
                self._change(ws)

    def _change(self, ws: Any) -> None:
        mine = [i for i, p in self.ledger.objects.items() if p is not None
                and i not in self.ledger.uncertain]
        kind = self.rng.choice(["create", "move", "move", "delete"] if mine else ["create"])
        if kind == "create":
            object_id, self.next = f"{self.client}.{self.next}", self.next + 1
            request = {"op": "create", "object": object_id, "type": "Box", "args": [0.1]}
            after: list[float] | None = [0.0, 0.0, 0.0]
        else:
            object_id = self.rng.choice(mine)
            if kind == "move":
                after = [round(self.rng.uniform(-5, 5), 3) for _ in range(3)]
                request = {"op": "call", "object": object_id, "method": "setPosition",
                           "args": after}
            else:
                request, after = {"op": "delete", "object": object_id}, None
        self.ledger.uncertain.add(object_id)  # until its answer says
        ws.send(json.dumps({**request, "id": 1}))
        while (answer := json.loads(ws.recv(timeout=10)))["op"] not in ("ok", "error") \
                or answer.get("id") != 1:
            pass
        if answer["op"] == "ok":
            self.ledger.objects[object_id] = after
            self.ledger.acknowledged += 1
        self.ledger.uncertain.discard(object_id)  # answered: done, or refused and not done


def watch(url: str, scene: str, pipe: Any, stop: Any) -> None:
    """The bystander (a process of its own): notes each frame's arrival until told to stop,
    then sends the times back."""
    times: list[float] = []
    while not stop.is_set():
        try:
            with connect(f"{url}/ws?scene={scene}&role=viewer", open_timeout=5,
                         max_size=None) as ws:
                while not stop.is_set():
                    if json.loads(ws.recv(timeout=5))["op"] == "frame":
                        times.append(time.monotonic())
        except (OSError, ConnectionClosed, InvalidHandshake, TimeoutError):
            time.sleep(0.05)
    pipe.send(times)


class Chaos:
    """A server, its changer and bystander, and the faults."""

    def __init__(self, state: Path, seed: int, quick: bool = False) -> None:
        self.state = state
        self.ledger = Ledger()
        self.windows: list[tuple[str, float, float]] = []
        self.checks: list[dict[str, Any]] = []
        self.document = big_document(150 if quick else 1500)
        self.mesh = trimesh.creation.icosphere(3 if quick else 6, 1.0).export(file_type="glb")
        self.quick = quick
        self.server = self._start()
        self.changer = Changer(lambda: self.server.ws, self.ledger, seed)
        self.piles = 0
        self.hand, self.recording = self._exported()

    def _exported(self) -> tuple[str, str]:
        """A RoundHand kept in scene EXPORTS, and a second's recording of that scene."""
        with connect(f"{self.server.ws}/ws?scene={EXPORTS}&keep=true") as ws:
            me = json.loads(ws.recv(timeout=30))["client"]
            ask(ws, {"op": "create", "object": f"{me}.h", "type": "RoundHand"})
            _, started = self.server.post(f"/api/scenes/{EXPORTS}/recordings")
            for angle in (0.2, 0.6, 1.0):
                ask(ws, {"op": "call", "object": f"{me}.h", "method": "flexFingers", "args": [angle]})
                time.sleep(0.3)
            self.server.post(f"/api/recordings/{started['id']}/stop")
        return f"{me}.h", started["id"]

    def _start(self, port: int | None = None) -> RunningServer:
        return start_server("--no-demo", "--state-dir", str(self.state), port=port)

    # --- faults ----------------------------------------------------------------------------

    def server_kill(self) -> None:
        crash_server(self.server)
        self.server = self._start(self.server.port)

    def restart(self) -> None:
        stop_server(self.server)
        self.server = self._start(self.server.port)

    def scene_kill(self) -> None:
        os.kill(self._pid(), signal.SIGKILL)
        time.sleep(0.3)

    def scene_stop(self) -> None:
        pid = self._pid()
        os.kill(pid, signal.SIGSTOP)
        time.sleep(1.0)
        os.kill(pid, signal.SIGCONT)

    def unwritable(self) -> None:
        with unwritable(self.state / "scenes"):
            time.sleep(1.5)

    def import_(self) -> None:
        self._post(f"/api/scenes/{IMPORTS}/import?replace=true", self.document)

    def upload(self) -> None:
        self._post("/api/assets", self.mesh)

    def pile(self) -> None:
        count = 100 if self.quick else 1000
        self.piles += 1
        url = f"{self.server.ws}/ws?scene=piles{self.piles}"
        with connect(url, max_size=None, max_queue=None) as ws:
            me = json.loads(ws.recv(timeout=30))["client"]
            ask(ws, {"op": "call", "object": "scene", "method": "setPhysics", "args": ["dynamic"]})
            ask(ws, {"op": "batch", "ops": pile_batch(me, "balls", count)})
            time.sleep(1.0)
            ask(ws, {"op": "batch", "ops": [{"op": "delete", "object": f"{me}.{k}"}
                                            for k in range(count)]})

    def export(self) -> None:
        deadline = time.monotonic() + 1.5
        url = f"{self.server.http}/api/scenes/{EXPORTS}/robots/{self.hand}/urdf"

        def loop() -> None:
            while time.monotonic() < deadline:
                try:
                    urllib.request.urlopen(url, timeout=60).read()
                except urllib.error.HTTPError as error:  # 429: the files' process is busy
                    assert error.code == 429, error
        threads = [threading.Thread(target=loop) for _ in range(2)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()

    def resimulate(self) -> None:
        self.server.post(f"/api/recordings/{self.recording}/resimulate")

    def _post(self, path: str, body: bytes) -> None:
        request = urllib.request.Request(self.server.http + path, data=body, method="POST")
        with urllib.request.urlopen(request, timeout=60) as answer:
            assert answer.status in (200, 201)

    def _pid(self) -> int:
        deadline = time.monotonic() + 60  # (a scene's process starting on a loaded machine)
        while time.monotonic() < deadline:
            figures = self.server.get("/api/metrics")["scenes"].get(WORK)
            if figures and figures["state"] == "running":
                return figures["pid"]
            time.sleep(0.05)
        raise TimeoutError("the changed scene did not come back")

    # --- a round ---------------------------------------------------------------------------

    def fault(self, kind: str) -> None:
        """Inject one fault while the changer runs, then check every acknowledged change."""
        self.changer.running.set()
        time.sleep(0.3)
        started = time.monotonic()
        getattr(self, {"import": "import_"}.get(kind, kind))()
        self.windows.append((kind, started, time.monotonic() + 0.3))
        time.sleep(0.3)
        self.changer.running.clear()
        self.changer.idle.wait(30)
        nodes = self._nodes()
        lost = self.ledger.lost_in(nodes)
        self.checks.append({"kind": kind, "lost": lost, "acknowledged": self.ledger.acknowledged})

    def _nodes(self) -> list[dict[str, Any]]:
        deadline = time.monotonic() + 30
        while True:
            try:
                return self.server.get(f"/api/scenes/{WORK}/snapshot")["nodes"]
            except OSError:  # the scene is starting again
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.1)


def big_document(robots: int) -> bytes:
    """A scene document of robots with a motor each (1 500: about 5 MB)."""
    scene = Scene(IMPORTS)
    ops = Operations(scene, "c9")
    for k in range(0, 2 * robots, 2):
        ops.create(f"c9.{k}", "Robot", [])
        ops.create(f"c9.{k + 1}", "MotorZ", [])
        ops.call(f"c9.{k}", "attachChain", [{"ref": f"c9.{k + 1}"}])
    try:
        return encode_document(export_scene(scene))
    finally:
        scene.close()


@contextmanager
def bystanding(ws: str) -> Iterator[list[float]]:
    """A bystander (a process of its own) watching BYSTANDER on the server at ``ws`` while
    the block runs; the list given gets the times of the frames it saw when the block ends."""
    context = multiprocessing.get_context("spawn")
    mine, theirs = context.Pipe()
    stop = context.Event()
    bystander = context.Process(target=watch, args=(ws, BYSTANDER, theirs, stop))
    bystander.start()
    frames: list[float] = []
    try:
        yield frames
    finally:
        stop.set()
        frames.extend(mine.recv() if mine.poll(30) else [])
        bystander.join(10)


def run(faults: int, seed: int = 1, quick: bool = False) -> dict[str, Any]:
    """``faults`` faults, the kinds in turn; what was acknowledged, lost and seen (``quick``:
    a small import and upload)."""
    with tempfile.TemporaryDirectory(prefix="vp-chaos-") as folder:
        chaos = Chaos(Path(folder) / "state", seed, quick)
        started = time.monotonic()
        try:
            with bystanding(chaos.server.ws) as frames:
                chaos.changer.start()
                for k in range(faults):
                    chaos.fault(KINDS[k % len(KINDS)])
        finally:
            chaos.changer.stopped = True
            stop_server(chaos.server)
        return summary(chaos, frames, time.monotonic() - started)


def summary(chaos: Any, frames: list[float], seconds: float, kinds: tuple[str, ...] = KINDS,
            gap_kinds: tuple[str, ...] = GAP_KINDS) -> dict[str, Any]:
    """The run in figures: faults, acknowledged and lost changes, bystander gaps by kind
    (``chaos``: a :class:`Chaos`, or the like, with its windows, checks and ledger)."""
    gaps: dict[str, list[float]] = {kind: [] for kind in gap_kinds}
    for kind, start, end in chaos.windows:
        if kind in gaps:
            gaps[kind].append(_worst_gap(frames, start, end))
    lost = sorted({object_id for check in chaos.checks for object_id in check["lost"]})
    return {"faults": len(chaos.checks), "rounds": len(chaos.checks) // len(kinds),
            "by_kind": {kind: sum(c["kind"] == kind for c in chaos.checks) for kind in kinds},
            "lost_by_kind": {kind: len({i for c in chaos.checks if c["kind"] == kind for i in c["lost"]})
                             for kind in kinds},
            "acknowledged": chaos.ledger.acknowledged, "lost": len(lost), "lost_ids": lost[:20],
            "uncertain": len(chaos.ledger.uncertain), "seconds": round(seconds, 1),
            "gap_ms": {kind: figure(values) for kind, values in gaps.items() if values},
            "gap_worst_ms": {kind: max(values) for kind, values in gaps.items() if values},
            "worst_gap_ms": max((max(v) for v in gaps.values() if v), default=0.0),
            "bystander_frames": len(frames)}


def _worst_gap(frames: list[float], start: float, end: float) -> float:
    """The longest time between two frames that overlaps [start, end], in milliseconds."""
    worst = 0.0
    for before, after in zip(frames, frames[1:]):
        if after >= start and before <= end:
            worst = max(worst, after - before)
    return worst * 1000


if __name__ == "__main__":
    import sys
    print(json.dumps(run(int(sys.argv[1]) if len(sys.argv) > 1 else len(KINDS)),
                     default=lambda f: f.as_dict(), indent=1))
