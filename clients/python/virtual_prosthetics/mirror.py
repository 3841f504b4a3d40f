"""The client's copy of the scene, kept current by the server's messages."""

from __future__ import annotations

import time
from collections import deque
from typing import Any, Callable, Iterator

from .codec import from_wire

NodeState = dict[str, Any]
ContactEvent = tuple[str, str, str]  # "begin" or "end", then the pair's two ids


class Mirror:
    """Nodes by id (as the server describes them), camera, clock, contacts and readings.

    Contact changes that ``wants(id)`` says someone listens to (for either id) are also
    queued in ``events`` until the client's own thread takes them, so that callbacks never
    run on the thread that reads the socket.

    In dynamic mode it also keeps the scene's ``physics`` and the ``forces`` on parts.

    Not thread-safe on its own: the :class:`~virtual_prosthetics.session.Session` holds a
    lock around every use.
    """

    def __init__(self, wants: Callable[[str], bool] = lambda node_id: True,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.wants = wants
        self.clock = clock
        self.nodes: dict[str, NodeState] = {}
        self.camera: dict[str, list[float]] = {}
        self.caption = ""  # what viewers show in a corner (setCaption)
        self.physics: dict[str, Any] = {"mode": "kinematic"}
        self.forces: dict[str, float] = {}  # dynamic mode: newtons on each part in contact
        self.time = 0.0
        self.seq = 0
        self.contacts: set[tuple[str, str]] = set()
        self.readings: dict[str, dict[str, Any]] = {}
        self.events: deque[ContactEvent] = deque()
        self._time_received = clock()
        self._time_given = float("-inf")

    def apply(self, message: dict[str, Any]) -> None:
        """Fold one server message (snapshot, added, frame, removed) into the mirror."""
        op = message["op"]
        if op == "snapshot":
            self.nodes.clear()
            self.camera = message["camera"]
            self.caption = message.get("caption", "")
            self.physics = message["physics"]
            self.forces = dict(message.get("forces", {}))  # pressing now (frames: changes)
            self._add(message["nodes"])
            self.contacts = {tuple(pair) for pair in message["contacts"]}  # type: ignore[misc]
            self.readings = {}  # none of a world that may be gone (a restore)
            self._read_sensors(message)
            self._clock(message)
        elif op == "added":
            self._add(message["nodes"])
        elif op == "removed":
            self._remove(message["ids"])
        elif op == "frame":
            self.apply_changes(message)
            self._contacts(message.get("contacts"))
            self._read_sensors(message)
            self._clock(message)

    def apply_changes(self, changes: dict[str, Any]) -> None:
        """Fold a change set (an ``ok`` answer's ``changes`` or a frame's fields)."""
        self._add(changes.get("added", ()))
        for node_id, fields in changes.get("updates", {}).items():
            if node_id in self.nodes:
                self.nodes[node_id].update(fields)
        for node_id, angle in self._each_angle(changes.get("angles", {})):
            if node_id in self.nodes:
                self.nodes[node_id]["angle"] = angle
        for node_id, pose in changes.get("poses", {}).items():
            if node_id in self.nodes:
                self.nodes[node_id].update(position=pose[:3], quaternion=pose[3:])
        for field in ("camera", "caption", "physics"):  # the scene's own, each sent whole
            if field in changes:
                setattr(self, field, changes[field])
        for node_id, force in changes.get("forces", {}).items():
            if force:
                self.forces[node_id] = force
            else:
                self.forces.pop(node_id, None)
        self._remove(changes.get("removed", ()))

    def _each_angle(self, angles: dict[str, Any]) -> Iterator[tuple[str, float]]:
        """``(motor id, angle)`` of a change set's ``angles``: a robot's come as one array
        in the order of its ``motors`` (updated before this), a lone motor's by its id."""
        for node_id, value in angles.items():
            if isinstance(value, list):
                yield from zip(self.nodes.get(node_id, {}).get("motors", ()), value)
            else:
                yield node_id, value

    def _contacts(self, changes: dict[str, list[list[str]]] | None) -> None:
        if not changes:
            return
        for kind in ("begin", "end"):
            for a, b in changes[kind]:
                if self.wants(a) or self.wants(b):
                    self.events.append((kind, a, b))
        self.contacts.difference_update(tuple(p) for p in changes["end"])
        self.contacts.update(tuple(p) for p in changes["begin"])  # type: ignore[misc]

    def _add(self, nodes: Any) -> None:
        for node in nodes:
            self.nodes[node["id"]] = dict(node)

    def _remove(self, ids: Any) -> None:
        for node_id in ids:
            self.nodes.pop(node_id, None)
            self.readings.pop(node_id, None)

    def _read_sensors(self, message: dict[str, Any]) -> None:
        for sensor_id, reading in message.get("sensors", {}).items():
            self.readings[sensor_id] = _reading(reading)

    def _clock(self, message: dict[str, Any]) -> None:
        self.time, self.seq = message["time"], message["seq"]
        self._time_received = self.clock()
        if message["op"] == "snapshot":
            # A new connection may meet a server restarted from its state folder, whose
            # scene time begins again.
            self._time_given = float("-inf")

    def now(self) -> float:
        """Server time now: the last frame's time plus what elapsed here since it came.

        Never less than a time already given: a frame read late would otherwise turn the
        estimate back, and animations would see time run backwards.
        """
        estimate = self.time + (self.clock() - self._time_received)
        self._time_given = max(self._time_given, estimate)
        return self._time_given

    def walk(self, node_id: str) -> Iterator[NodeState]:
        """A node and its descendants in depth-first pre-order."""
        stack = [node_id]
        while stack:
            node = self.nodes.get(stack.pop())
            if node is not None:
                yield node
                stack.extend(reversed(node["children"]))

    def parts(self, robot_id: str) -> list[NodeState]:
        """The parts below a robot (motors included, slots not), in tree order."""
        return [n for n in self.walk(robot_id) if n["id"] != robot_id and n["type"] != "Slot"]

    def motors(self, robot_id: str) -> list[NodeState]:
        """The motors of a robot in index order, as the server lists them."""
        robot = self.nodes.get(robot_id, {})
        return [self.nodes[i] for i in robot.get("motors", ()) if i in self.nodes]


def _reading(wire: dict[str, Any]) -> dict[str, Any]:
    """A sensor reading with its distance as a float (Infinity travels as a string)."""
    return {**wire, "distance": from_wire(wire["distance"])}
