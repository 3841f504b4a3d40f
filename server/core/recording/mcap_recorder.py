"""A scene's history as an MCAP file: everything viewers were sent and every request
clients made, each at its time, in chunks compressed with zstd (the ``mcap`` package).

Channels (JSON messages, each with the JSON Schema of what it carries):

- ``/vp/document``: the scene when the recording starts as a scene document (what
  ``/export`` gives, uploaded meshes included) with the sensors' watchers: what a
  re-simulation starts from (:mod:`.resimulate`).
- ``/vp/snapshot``: the whole scene (the protocol's ``snapshot``) when the recording
  starts and every SNAPSHOT_EVERY seconds of scene time after: a replay seeks to the last
  one before a time and applies the ticks after it (MCAP's chunk index finds both
  without reading the file from its start).
- ``/vp/ticks``: each tick's messages as viewers get them (``added``, ``frame``,
  ``removed``): poses, angles, contacts, watched readings, forces.
- ``/vp/requests``: each text a client sent (``client``, ``text``), applied or refused.
- ``/sensors/<id>``: one channel per watched sensor, its reading each time it changed
  (``distance``, ``touch``, ``force``…, as the protocol's ``reading``): what a plot reads.
- ``/scene`` and ``/tf``: the physical parts as Foxglove draws them (:mod:`.foxglove`):
  every part anew when the recording starts and at most once a second while parts come
  and go; where the parts that moved are, each tick, and all of them with each snapshot.

Log times are the scene's clock, counted from the wall time at which the recording
started (a paused scene's steps are as far apart as its clock says, not as the wall's).
Bounded: the recording stops itself at ``max_bytes`` of file or ``max_seconds`` of scene
time, and says which.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from typing import IO, Any, Mapping

from mcap.writer import CompressionType, Writer

from ..protocol.messages import encode, schema
from ..protocol.scene_document import export_scene
from ..model.node import Node
from ..scene.scene import Scene
from . import foxglove

SNAPSHOT_EVERY = 5.0  # seconds of scene time between the snapshots a seek starts from
SCENE_EVERY = 1.0  # seconds of scene time at least between two /scene messages
CHUNK_BYTES = 256 * 1024  # MCAP chunk size: the most a stop at max_bytes can run over
PROFILE = "virtual-prosthetics"

def _standalone(root: dict[str, Any]) -> dict[str, Any]:
    """``root`` with the protocol's definitions it refers to (and only those), whole or in
    part (``#/$defs/changes/properties/angles`` needs ``changes``)."""
    defs, wanted, todo = schema()["$defs"], {}, [root]
    while todo:
        for name in _REFERRED.findall(json.dumps(todo.pop())):
            if name not in wanted:
                wanted[name] = defs[name]
                todo.append(defs[name])
    return {**root, "$defs": wanted}


_REFERRED = re.compile(r'"#/\$defs/([^"/]+)')


SCHEMAS = {  # each channel's messages, as Foxglove and any JSON Schema reader read them
    "snapshot": _standalone({"$ref": "#/$defs/snapshot"}),
    "reading": _standalone({"$ref": "#/$defs/reading"}),
    "ticks": _standalone({"type": "object", "required": ["messages"], "properties": {"messages": {
        "type": "array", "items": {"anyOf": [{"$ref": "#/$defs/added"}, {"$ref": "#/$defs/frame"},
                                             {"$ref": "#/$defs/removed"}]}}}}),
    "document": _standalone({"type": "object", "required": ["document", "watchers"], "properties": {
        "document": {"$ref": "#/$defs/sceneDocument"},
        "watchers": {"type": "object", "additionalProperties": {"type": "array", "items": {"type": "string"}}}}}),
    "scene": foxglove.SCENE_SCHEMA, "transforms": foxglove.TRANSFORMS_SCHEMA,
    "request": {"type": "object", "required": ["client", "text"], "properties": {
        "client": {"type": "string"}, "text": {"type": "string", "description": "as sent"}}},
}


@dataclass(frozen=True)
class RecordingLimits:
    """How much one recording may hold (flags: ``--limit recordingBytes=N``,
    ``--limit recordingSeconds=N``)."""

    max_bytes: int
    max_seconds: float


class Recorder:
    """One recording of one scene into ``stream`` (a binary file open for writing)."""

    def __init__(self, stream: IO[bytes], scene: Scene, wall_ns: int, limits: RecordingLimits) -> None:
        self._stream, self._limits = stream, limits
        self._wall_ns, self._start = wall_ns, scene.time
        self._writer = Writer(stream, chunk_size=CHUNK_BYTES, compression=CompressionType.ZSTD)
        self._writer.start(profile=PROFILE)
        self._writer.add_metadata("recording", {"scene": scene.name, "startedNs": str(wall_ns),
                                                "sceneTime": repr(scene.time)})
        self._channels: dict[str, int] = {}
        self._schema_ids: dict[str, int] = {}
        self._sequence = 0
        self._last_snapshot = -SNAPSHOT_EVERY
        self.stopped: str | None = None  # why it stopped, once it has
        self.counts = {"ticks": 0, "requests": 0, "snapshots": 0, "readings": 0}
        self._drawn_at = -SCENE_EVERY  # scene time of the last /scene
        self._redraw = False  # parts came or went since
        self._parts_below: dict[str, list[Node]] = {}  # moved node -> its parts (foxglove.moved)
        self._write("/vp/document", "document", {"document": export_scene(scene),
                                                 "watchers": scene.watches.holders()}, scene.time)
        self._snapshot(scene)
        self._draw(scene)

    @property
    def size(self) -> int:
        """Bytes written so far (a chunk being filled is not counted until it is full)."""
        return self._stream.tell()

    @property
    def seconds(self) -> float:
        """Scene time recorded so far."""
        return self._last - self._start if self._sequence else 0.0

    def _snapshot(self, scene: Scene) -> None:
        """The whole scene as it is now, and where every part is."""
        self._write("/vp/snapshot", "snapshot", scene.snapshot(), scene.time)
        self._write("/tf", "transforms", foxglove.transforms(foxglove.drawn(scene), self._ns(scene.time)),
                    scene.time)
        self._last_snapshot = scene.time
        self.counts["snapshots"] += 1

    def _draw(self, scene: Scene) -> None:
        self._write("/scene", "scene", foxglove.scene_update(scene, self._ns(scene.time), scene.assets),
                    scene.time)
        self._drawn_at, self._redraw = scene.time, False

    def request(self, client_id: str, text: str | bytes, scene_time: float) -> None:
        """A text a client sent (before it is applied)."""
        if isinstance(text, bytes):
            text = text.decode("utf-8", "replace")
        self._write("/vp/requests", "request", {"client": client_id, "text": text}, scene_time)
        self.counts["requests"] += 1

    def tick(self, messages: list[Mapping[str, Any]], scene: Scene) -> str | None:
        """A tick's messages (the scene as they leave it); a snapshot first when one is
        due. The reason the recording stopped, when a limit stopped it now."""
        if self.stopped:
            return None
        now = scene.time
        if now - self._last_snapshot >= SNAPSHOT_EVERY:
            self._snapshot(scene)
        self._write("/vp/ticks", "ticks", {"messages": messages}, now)
        self.counts["ticks"] += 1
        for message in messages:
            if message["op"] in ("added", "removed") or message.get("updates"):
                self._redraw = True
                self._parts_below.clear()
            for sensor, reading in (message.get("sensors") or {}).items():
                self._write(f"/sensors/{sensor}", "reading", reading, now)
                self.counts["readings"] += 1
        if self._redraw and now - self._drawn_at >= SCENE_EVERY:
            self._draw(scene)
        moved = foxglove.moved(scene, messages, self._parts_below)
        if moved:
            self._write("/tf", "transforms", foxglove.transforms(moved, self._ns(now)), now)
        return self._over()

    def finish(self, reason: str, scene: Scene) -> dict[str, Any]:
        """End the file (its index and summary written) and say how it ended."""
        if self._redraw and not self.stopped:
            self._draw(scene)
        self.stopped = self.stopped or reason
        self._writer.add_metadata("stopped", {"reason": self.stopped})
        self._writer.finish()
        return self.summary()

    def summary(self) -> dict[str, Any]:
        """What the recording holds so far."""
        return {"bytes": self.size, "seconds": round(self.seconds, 6), **self.counts,
                "stopped": self.stopped}

    def _over(self) -> str | None:
        limits = self._limits
        if self.size + CHUNK_BYTES > limits.max_bytes:
            self.stopped = f"it reached {limits.max_bytes} bytes, the most a recording holds " \
                           f"(--limit recordingBytes=N)"
        elif self.seconds >= limits.max_seconds:
            self.stopped = f"it reached {limits.max_seconds:g} s of scene time, the most a " \
                           f"recording holds (--limit recordingSeconds=N)"
        return self.stopped

    def _write(self, topic: str, schema: str, value: Any, scene_time: float) -> None:
        channel = self._channels.get(topic)
        if channel is None:
            if schema not in self._schema_ids:
                name = SCHEMAS[schema].get("title", f"vp.{schema}")  # Foxglove's by their names
                self._schema_ids[schema] = self._writer.register_schema(
                    name, "jsonschema", json.dumps(SCHEMAS[schema]).encode())
            channel = self._channels[topic] = self._writer.register_channel(
                topic, "json", self._schema_ids[schema])
        at = self._ns(scene_time)
        self._writer.add_message(channel, log_time=at, publish_time=at,
                                 data=encode(value).encode(), sequence=self._sequence)
        self._sequence += 1
        self._last = scene_time

    def _ns(self, scene_time: float) -> int:
        """The log time of a scene time: nanoseconds since 1970, counted from the wall
        time the recording started at."""
        return self._wall_ns + round((scene_time - self._start) * 1e9)
