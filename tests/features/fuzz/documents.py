"""Fuzzing scene documents where they come in: REST import and files in ``--state-dir``.

Each case is a valid document (of a small scene, now and then of one with every kind of
object) with one to three values replaced by odd ones or left out, sometimes cut short or
nested deep, and for files a journal after it with lines changed likewise. The REST fuzzer
posts them to a real server's import and wants a 200 or a structured 4xx, never a 500 or a
dropped connection. The file fuzzer restores them as a scene's process does at start
(:meth:`SceneWorker.prepare`), which must never raise: a file it cannot use is set aside.

Run as a program each prints a JSON summary with its process's peak memory (``rest``
starts a server of its own unless given one, and adds that server's peak and health)::

    python -m tests.features.fuzz.documents files --cases 10000
    python -m tests.features.fuzz.documents rest [--url http://127.0.0.1:8000] --cases 10000
"""

from __future__ import annotations

import argparse
import http.client
import json
import multiprocessing
import random
import sys
import tempfile
import threading
from pathlib import Path
from typing import Any, Iterator
from urllib.parse import urlsplit

from server.core.protocol.command_log import applied_line, left_line
from server.core.protocol.operations import Operations
from server.core.scene.scene import Scene
from server.core.protocol.scene_document import encode_document, export_scene, import_scene
from server.web.storage.scene_store import SceneStore
from server.web.process.worker import SceneWorker
from tests.features.fuzz.gltf_files import peak_megabytes

ODD = [None, True, -1, 0, 1e308, -1e308, 2 ** 64, 1.5, "", "x" * 300, "c1.1", "c2.1",
       "demo.1", "ground", "../../etc/passwd", [], [1], [0, 0, 0], [[1, 2], [3]], {},
       {"ref": "c1.1"}, {"kind": "box", "size": [1e9, 1, 1]}, "Infinity", "NaN", "Robot",
       "EdgedHand", "Slot", 0.5]


def small_document() -> dict[str, Any]:
    """A scene of a few kinds of object, changed after they were made."""
    scene = Scene("lab")
    ops = Operations(scene, "c1")
    for object_id, kind, args in [("c1.1", "Robot", []), ("c1.2", "MotorZ", [-1, 1]),
                                  ("c1.3", "EdgedFinger", [1, 0.5]), ("c1.4", "Box", [0.2]),
                                  ("c1.5", "Ball", [0.1, "red"]), ("c1.6", "Sensor", [])]:
        ops.create(object_id, kind, args)
    ops.call("c1.1", "attachChain", [{"ref": "c1.2"}, {"ref": "c1.3"}])
    ops.call("c1.6", "attachToSlot", [{"ref": "c1.3"}, 0])
    ops.call("c1.1", "setAngle", [0, 0.4])
    ops.call("c1.4", "setPosition", [1, 2, 3])
    ops.call("c1.4", "keep", [])
    try:
        return json.loads(encode_document(export_scene(scene)))
    finally:
        scene.close()


def hand_document() -> dict[str, Any]:
    """A scene with a hand of each kind (their inner parts are many nodes)."""
    scene = Scene("lab")
    ops = Operations(scene, "c1")
    for k, kind in enumerate(["EdgedHand", "RoundHand", "AnthroHand"]):
        ops.create(f"c1.{k}", kind, [])
    ops.call("c1.0", "flexFingers", [0.5])
    try:
        return json.loads(encode_document(export_scene(scene)))
    finally:
        scene.close()


def _places(value: Any, path: tuple = ()) -> Iterator[tuple]:
    yield path
    items = value.items() if isinstance(value, dict) else \
        enumerate(value) if isinstance(value, list) else ()
    for key, inner in items:
        yield from _places(inner, path + (key,))


class Mutator:
    """Odd documents made from valid ones."""

    def __init__(self, seed: int) -> None:
        self.rng = random.Random(seed)
        self.bases = [(json.dumps(d), [p for p in _places(d) if p])
                      for d in (small_document(), small_document(), hand_document())]

    def document(self) -> bytes:
        rng = self.rng
        text, places = self.bases[0] if rng.random() < 0.9 else rng.choice(self.bases)
        if rng.random() < 0.05:  # not JSON, or JSON nested past any parser's depth
            return rng.choice([text.encode()[:rng.randrange(len(text))],
                               b"[" * 100_000, b"\xff\xfe{}", b"", b"null", b"[]"])
        document = json.loads(text)
        for path in rng.sample(places, rng.choice([0, 1, 1, 2, 3])):  # 0: its journal alone
            self._change(document, path)
        return json.dumps(document).encode()

    def _change(self, document: Any, path: tuple) -> None:
        holder = document
        try:
            for key in path[:-1]:
                holder = holder[key]
            if self.rng.random() < 0.15:
                del holder[path[-1]]
            else:
                holder[path[-1]] = self.rng.choice(ODD)
        except (KeyError, IndexError, TypeError):
            pass  # an earlier change took this place away

    def journal(self) -> list[bytes]:
        """Journal lines: requests of the document's client and others, some odd."""
        rng = self.rng
        lines = [applied_line(rng.choice(["c1", "c2", "c9"]), rng.random() < 0.5, {
            "op": rng.choice(["create", "call", "delete", "batch", "ping", "fly"]),
            "object": rng.choice(["c1.1", "c1.4", "c1.9", "c2.1", "scene", "c1.1/0"]),
            "type": rng.choice(["Box", "Robot", "EdgedHand", "Nothing"]),
            "method": rng.choice(["setPosition", "setAngle", "keep", "share", "delete"]),
            "args": [rng.choice(ODD) for _ in range(rng.randrange(4))]})
            for _ in range(rng.randrange(6))]
        lines += [left_line("c1")] if rng.random() < 0.2 else []
        if lines and rng.random() < 0.3:
            lines[-1] = lines[-1][:rng.randrange(len(lines[-1]))]  # cut short by a crash
        return [line.rstrip(b"\n") for line in lines]


def fuzz_files(cases: int, seed: int = 0) -> dict[str, Any]:
    """Restore ``cases`` fuzzed files (document and journal) as a scene's process does."""
    mutator, folder = Mutator(seed), Path(tempfile.mkdtemp(prefix="vp-doc-fuzz-"))
    outcome: dict[str, Any] = {"cases": cases, "restored": 0, "setAside": 0, "crashes": []}
    server_end, scene_end = multiprocessing.Pipe()
    scene = Scene("lab")  # one world, emptied between cases (a new one costs PyBullet ~6 ms)
    empty = json.loads(encode_document(export_scene(scene)))
    for number in range(cases):
        with scene.journal.transaction():
            import_scene(scene, empty)
        path = folder / f"s{number}.json"
        path.write_bytes(mutator.document())
        store = SceneStore(path)
        if mutator.rng.random() < 0.5:
            header = json.dumps({"format": "virtual-prosthetics-journal",
                                 "after": _digest(path.read_bytes())}).encode()
            path.with_suffix(".journal").write_bytes(b"\n".join([header, *mutator.journal()]))
        try:
            SceneWorker(scene_end, scene, 60.0, store).prepare(None)
            outcome["restored" if path.exists() else "setAside"] += 1
        except Exception as error:  # what the test reports
            outcome["crashes"].append([number, repr(error)[:200]])
        finally:
            for spare in folder.iterdir():
                spare.unlink()
    scene.close()
    return _finish(outcome)


def _digest(data: bytes) -> str:
    import hashlib
    return hashlib.sha256(data).hexdigest()


def fuzz_rest(url: str, cases: int, seed: int = 0, lanes: int = 2) -> dict[str, Any]:
    """Post ``cases`` fuzzed documents to a server's import, over ``lanes`` connections at
    once, each to a scene of its own (replaced each time)."""
    outcomes = [{"taken": 0, "refused": 0, "crashes": []} for _ in range(lanes)]
    threads = [threading.Thread(target=_post_all, args=(url, cases // lanes, seed + k,
                                                        f"fuzzed{k}", outcomes[k]))
               for k in range(lanes)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return _finish({"cases": cases // lanes * lanes,
                    "taken": sum(o["taken"] for o in outcomes),
                    "refused": sum(o["refused"] for o in outcomes),
                    "crashes": [c for o in outcomes for c in o["crashes"]]})


def _post_all(url: str, cases: int, seed: int, scene: str, outcome: dict[str, Any]) -> None:
    mutator, address = Mutator(seed), urlsplit(url)
    connection = http.client.HTTPConnection(address.hostname, address.port, timeout=60)
    for number in range(cases):
        try:
            connection.request("POST", f"/api/scenes/{scene}/import?replace=true",
                               body=mutator.document())
            answer = connection.getresponse()
            body = json.loads(answer.read())
            if answer.status == 200:
                outcome["taken"] += 1
            elif 400 <= answer.status < 500 and {"code", "message"} <= set(body):
                outcome["refused"] += 1
            else:
                outcome["crashes"].append([scene, number, answer.status, str(body)[:200]])
        except (OSError, http.client.HTTPException, ValueError) as error:
            outcome["crashes"].append([scene, number, repr(error)[:200]])
            connection.close()
            connection = http.client.HTTPConnection(address.hostname, address.port, timeout=60)


def _finish(outcome: dict[str, Any]) -> dict[str, Any]:
    outcome["peakMegabytes"] = peak_megabytes()
    return outcome


def fuzz_own_server(cases: int, seed: int = 0) -> dict[str, Any]:
    """:func:`fuzz_rest` against a server started for it: with its peak memory and health."""
    from tests.conftest import start_server, stop_server

    server = start_server("--no-demo")
    try:
        outcome = fuzz_rest(server.http, cases, seed)
        outcome["serverPeakMegabytes"] = peak_megabytes(server.process.pid)
        outcome["serverHealth"] = server.get("/api/health")["status"]
        return outcome
    finally:
        stop_server(server)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("where", choices=["files", "rest"])
    parser.add_argument("--cases", type=int, default=10_000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--url", default=None)
    options = parser.parse_args()
    if options.where == "files":
        result = fuzz_files(options.cases, options.seed)
    elif options.url is None:
        result = fuzz_own_server(options.cases, options.seed)
    else:
        result = fuzz_rest(options.url, options.cases, options.seed)
    json.dump(result, sys.stdout)
