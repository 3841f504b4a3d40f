"""A recording's requests run again against this server, and where the new run differs.

How a designer checks that a changed server (or hand) still does what the old one did:
the scene the recording started from (its ``/vp/document``, watchers included) is made in
a fresh scene; then, in the file's order, every request is applied for the client that
sent it and every recorded tick is ticked with the same time step, and the tick's
messages are compared with the recorded ones: poses, angles, watched readings, contacts,
forces and parts coming and going (contacts and forces as they stand, not as the events
frames carry). Kinematic mode comes out exactly the same. Dynamic mode too, from its
second tick on, when the recording began as the world was made (at ``setPhysics``: its
first tick's contact list may differ); a recording begun mid-motion drifts, since a
document keeps no velocities and Bullet's contact caches start empty (a hand closing on
a ball: 16 cm in 3 s), so compare it with a ``tolerance``. A re-simulation is
deterministic: the same recording gives the same report every time.

What the server's own setups animate (the demo's hands) is no request: it is not in a
re-simulation, and shows as a difference.
"""

from __future__ import annotations

import json
import math
from typing import IO, Any, Iterator

from mcap.reader import make_reader

from ..kit.limits import Limits
from ..physics.assets import AssetLibrary, Uploads
from ..protocol.messages import encode
from ..protocol.scene_document import import_scene
from ..protocol.session import Session
from ..scene.scene import Scene
from .damage import reading

COMPARED = ("poses", "angles", "updates", "sensors")  # contacts and forces: as they stand
MAX_LISTED = 100  # differences listed in a report (all are counted)


def resimulate(stream: IO[bytes], scene: Scene, tolerance: float = 0.0) -> dict[str, Any]:
    """Run the recording in ``stream`` again in ``scene`` (empty, made for it); a report:
    ``ticks``, ``requests``, ``ticksDiffering`` and the first MAX_LISTED ``differences``
    (``tick``, ``time`` from the start, ``field``, ``id``, ``recorded``, ``now``)."""
    sessions: dict[str, Session] = {}
    report: dict[str, Any] = {"ticks": 0, "requests": 0, "ticksDiffering": 0, "differences": []}
    previous = start = None
    before: set[str] = set()  # made before the recording; a first tick may announce them
    recorded, anew = Touching(), Touching()  # contacts are compared as they stand, not as events
    pressed: dict[str, float] = {}  # forces as they stand (frames send changes): recorded run
    pressing: dict[str, float] = {}  # and this one
    for _, channel, message in make_reader(stream).iter_messages(log_time_order=False):
        data = json.loads(message.data)
        if channel.topic == "/vp/document":
            before = _start(scene, data)
            anew.pairs = {tuple(pair) for pair in scene.bodies.contacts.wire()}
            pressed = {k: round(v, 3) for k, v in scene.bodies.physics.parts.forces.items()}  # (the
            pressing = dict(pressed)  # recording keeps no forces at its start: taken as these)
        elif channel.topic == "/vp/snapshot" and recorded.pairs is None:  # the first: the start
            recorded.pairs = {tuple(pair) for pair in data["contacts"]}
            previous = start = data["time"]
        elif channel.topic == "/vp/requests":
            session = sessions.get(data["client"]) or sessions.setdefault(
                data["client"], Session(scene, data["client"]))
            session.receive(data["text"])
            scene.clock.take()  # its steps' ticks are the recorded ticks that follow
            report["requests"] += 1
        elif channel.topic == "/vp/ticks":
            frame = next(m for m in data["messages"] if m["op"] == "frame")
            now = json.loads(encode(scene.tick(frame["time"] - previous)))  # as recorded: wire numbers
            previous = frame["time"]
            announced = {n["id"] for m in data["messages"] if m["op"] == "added" for n in m["nodes"]} & before
            found = list(differences(_unannounced(data["messages"], before), _unposed(now, announced), tolerance))
            was, became = recorded.after(data["messages"]), anew.after(now)
            if was != became:
                found.append({"field": "contacts", "id": None, "recorded": sorted(was - became),
                              "now": sorted(became - was)})
            for part in _pressed(pressed, data["messages"]) | _pressed(pressing, now):
                if not _same(pressed.get(part, 0.0), pressing.get(part, 0.0), tolerance):
                    found.append({"field": "forces", "id": part, "recorded": pressed.get(part, 0.0),
                                  "now": pressing.get(part, 0.0)})
            report["ticks"] += 1
            if found:
                report["ticksDiffering"] += 1
                room = MAX_LISTED - len(report["differences"])
                report["differences"] += [{"tick": report["ticks"], "time": frame["time"] - start, **d}
                                          for d in found[:max(0, room)]]
    return report


def resimulate_file(path: str, limits: Limits, assets: AssetLibrary, tolerance: float,
                    uploads: Uploads | None = None) -> dict[str, Any]:
    """:func:`resimulate` of the recording at ``path`` in a scene made for it (and closed;
    files its document brings that are not here are kept in ``uploads``)."""
    scene = Scene("resimulation", limits, assets, uploads)
    try:
        with open(path, "rb") as stream, reading(path):
            return resimulate(stream, scene, tolerance)
    finally:
        scene.close()


def _start(scene: Scene, data: dict[str, Any]) -> set[str]:
    """The scene as the recording found it (what making it sends is not compared); the ids
    of its nodes."""
    with scene.journal.transaction():
        import_scene(scene, data["document"])
    for sensor, watchers in data["watchers"].items():
        for watcher in watchers:
            scene.watches.add(sensor, watcher)
    scene.tick(0.0)
    return set(scene.nodes)


def _unannounced(messages: list[dict[str, Any]], before: set[str]) -> list[dict[str, Any]]:
    """A recorded tick's messages without announcing nodes the recording began with (made
    just before it started, announced by its first tick): the new run made them already."""
    out = []
    for message in messages:
        if message["op"] == "added":
            message = {**message, "nodes": [n for n in message["nodes"] if n["id"] not in before]}
            if not message["nodes"]:
                continue
        out.append(message)
    return out


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


def _unposed(messages: list[dict[str, Any]], ids: set[str]) -> list[dict[str, Any]]:
    """This run's tick without poses, angles and updates of ``ids`` (nodes the recorded
    run announced whole in that tick, where this run had announced them already)."""
    if not ids:
        return messages
    return [{**m, **{field: {k: v for k, v in m[field].items() if k not in ids}
                     for field in ("poses", "angles", "updates") if field in m}}
            if m["op"] == "frame" else m for m in messages]


def _pressed(forces: dict[str, float], messages: list[dict[str, Any]]) -> set[str]:
    """Apply a tick's force changes to ``forces``; the parts they name."""
    named = set()
    for message in messages:
        for part, newtons in (message.get("forces") or {}).items() if message["op"] == "frame" else ():
            named.add(part)
            if newtons:
                forces[part] = newtons
            else:
                forces.pop(part, None)
    return named


class Touching:
    """The pairs touching, as a snapshot says and frames' contact events change them."""

    def __init__(self) -> None:
        self.pairs: set[tuple[str, ...]] | None = None

    def after(self, messages: list[dict[str, Any]]) -> set[tuple[str, ...]]:
        pairs = self.pairs if self.pairs is not None else set()
        for message in messages:
            contacts = message.get("contacts") if message["op"] == "frame" else None
            if contacts:
                pairs -= {tuple(p) for p in contacts.get("end", [])}
                pairs |= {tuple(p) for p in contacts.get("begin", [])}
        self.pairs = pairs
        return pairs


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
