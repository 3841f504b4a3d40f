"""A recording's requests run again against this server, and where the new run differs.

How a designer checks that a changed server (or hand) still does what the old one did:
the scene the recording started from (its ``/vp/document``, watchers included) is made in
a fresh scene; then, in the file's order, every request is applied for the client that
sent it and every recorded tick is ticked with the same time step, and the tick's
messages are compared with the recorded ones: poses, angles, watched readings, contacts,
forces and parts coming and going. Kinematic mode comes out exactly the same; dynamic
mode is the same on the same server when the recording started at rest (a document
keeps no velocities), within ``tolerance`` otherwise.

What the server's own setups animate (the demo's hands) is no request: it is not in a
re-simulation, and shows as a difference.
"""

from __future__ import annotations

import json
import math
from typing import IO, Any, Iterator

from mcap.reader import make_reader

from ..kit.limits import Limits
from ..physics.assets import AssetLibrary
from ..protocol.messages import encode
from ..protocol.scene_document import import_scene
from ..protocol.session import Session
from ..scene.scene import Scene

COMPARED = ("poses", "angles", "updates", "sensors", "contacts", "forces")
MAX_LISTED = 100  # differences listed in a report (all are counted)


def resimulate(stream: IO[bytes], scene: Scene, tolerance: float = 0.0) -> dict[str, Any]:
    """Run the recording in ``stream`` again in ``scene`` (empty, made for it); a report:
    ``ticks``, ``requests``, ``ticksDiffering`` and the first MAX_LISTED ``differences``
    (``tick``, ``time`` from the start, ``field``, ``id``, ``recorded``, ``now``)."""
    sessions: dict[str, Session] = {}
    report: dict[str, Any] = {"ticks": 0, "requests": 0, "ticksDiffering": 0, "differences": []}
    previous = start = None
    for _, channel, message in make_reader(stream).iter_messages(log_time_order=False):
        data = json.loads(message.data)
        if channel.topic == "/vp/document":
            _start(scene, data)
        elif channel.topic == "/vp/requests":
            session = sessions.get(data["client"]) or sessions.setdefault(
                data["client"], Session(scene, data["client"]))
            session.receive(data["text"])
            scene.clock.take()  # its steps' ticks are the recorded ticks that follow
            report["requests"] += 1
        elif channel.topic == "/vp/ticks":
            frame = next(m for m in data["messages"] if m["op"] == "frame")
            previous = frame["time"] if previous is None else previous
            start = frame["time"] if start is None else start
            now = json.loads(encode(scene.tick(frame["time"] - previous)))  # as recorded: wire numbers
            previous = frame["time"]
            found = list(differences(data["messages"], now, tolerance))
            report["ticks"] += 1
            if found:
                report["ticksDiffering"] += 1
                room = MAX_LISTED - len(report["differences"])
                report["differences"] += [{"tick": report["ticks"], "time": frame["time"] - start, **d}
                                          for d in found[:max(0, room)]]
    return report


def resimulate_file(path: str, limits: Limits, assets: AssetLibrary, tolerance: float) -> dict[str, Any]:
    """:func:`resimulate` of the recording at ``path`` in a scene made for it (and closed)."""
    scene = Scene("resimulation", limits, assets)
    try:
        with open(path, "rb") as stream:
            return resimulate(stream, scene, tolerance)
    finally:
        scene.close()


def _start(scene: Scene, data: dict[str, Any]) -> None:
    """The scene as the recording found it; what making it sends is not compared."""
    with scene.journal.transaction():
        import_scene(scene, data["document"])
    for sensor, watchers in data["watchers"].items():
        for watcher in watchers:
            scene.watches.add(sensor, watcher)
    scene.tick(0.0)


def differences(recorded: list[dict[str, Any]], now: list[dict[str, Any]],
                tolerance: float) -> Iterator[dict[str, Any]]:
    """Where a tick's messages differ from the recorded ones (numbers by more than
    ``tolerance``)."""
    old, new = _by_op(recorded), _by_op(now)
    for op in ("added", "removed"):
        ids = {"added": lambda m: sorted(n["id"] for n in m.get("nodes", [])),
               "removed": lambda m: sorted(m.get("ids", []))}[op]
        if ids(old.get(op, {})) != ids(new.get(op, {})):
            yield {"field": op, "id": None, "recorded": ids(old.get(op, {})), "now": ids(new.get(op, {}))}
    before, after = old.get("frame", {}), new.get("frame", {})
    for field in COMPARED:
        a, b = before.get(field, {}), after.get(field, {})
        for key in sorted(set(a) | set(b)):
            if not _same(a.get(key), b.get(key), tolerance):
                yield {"field": field, "id": key, "recorded": a.get(key), "now": b.get(key)}


def _by_op(messages: list[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    return {m["op"]: m for m in messages}


def _same(a: Any, b: Any, tolerance: float) -> bool:
    if isinstance(a, bool) or isinstance(b, bool) or not isinstance(a, (int, float)) \
            or not isinstance(b, (int, float)):
        if isinstance(a, dict) and isinstance(b, dict):
            return a.keys() == b.keys() and all(_same(a[k], b[k], tolerance) for k in a)
        if isinstance(a, list) and isinstance(b, list):
            return len(a) == len(b) and all(_same(x, y, tolerance) for x, y in zip(a, b))
        return a == b
    return a == b or (math.isfinite(a) and math.isfinite(b) and abs(a - b) <= tolerance)
