"""The scene: one world of robots, its collision bodies, its clock and its change feed.

Sans-I/O: the web layer calls :meth:`Scene.tick` at its own rate and ships the
messages it returns; nothing here knows about sockets or event loops.
"""

from __future__ import annotations

import logging
from collections import Counter
from contextlib import contextmanager
from typing import Any, Iterator

from ...errors import DuplicateId, LimitExceeded, UnknownObject
from ..kit.ids import IdBook, owner_of
from ..kit.journal import Journal
from ..kit.limits import DEFAULT, Limits
from ..kit.math3d import Quat, Vec3
from ..kit.numbers import encode_numbers
from ..kit.wire_messages import Snapshot
from ..model import part_figures
from ..model.motor import Motor
from ..model.node import Node
from ..model.readings import Reading
from ..model.robot import Robot
from ..model.watches import Watches
from ..physics.assets import AssetLibrary
from . import frames
from .bodies import SceneBodies
from .changes import ChangeSet

log = logging.getLogger(__name__)
_POSE_FIELDS = ("position", "quaternion", "angle", "flipped", "scale")


class Scene:
    """Robots and parts in one PyBullet world, with time, sequence number and camera."""

    def __init__(self, name: str = "default", limits: Limits = DEFAULT,
                 assets: AssetLibrary | None = None) -> None:
        self.name = name
        self.limits = limits
        self.nodes: dict[str, Node] = {}
        self.journal = Journal()
        self.ids = IdBook(self.journal, limits.client_names)
        self.owned: Counter[str] = Counter()  # objects per owner
        self.physical = 0  # physical parts, in the scene or not
        self._made = 0  # nodes made so far: each node's serial says when it was made
        self.assets = assets or AssetLibrary()
        self.bodies = SceneBodies(self.nodes, self.in_scene, limits, self.assets, name)
        self.time = 0.0
        self.seq = 0
        self.tree_version = 0
        self.revision = 0  # ticks that sent changes: a document of the scene is out of date
        self.camera: dict[str, Vec3] = {"position": part_figures.CAMERA_POSITION,
                                        "target": part_figures.CAMERA_TARGET}
        self._pending = ChangeSet()
        self._recorders: list[ChangeSet] = [self._pending]
        self.watches = Watches(self.journal, limits.watched_sensors)
        self.failures = 0  # ticks whose contacts or sensing failed (a bug; logged)

    def close(self) -> None:
        """Release the physics world."""
        self.bodies.close()

    # --- registry ------------------------------------------------------------------------

    def register(self, node: Node) -> None:
        """Add a newly made node (journaled): its id must be new to this scene."""
        if node.id in self.nodes:
            raise DuplicateId(f"id {node.id} is already in use in scene {self.name}",
                              object=node.id)
        self._check_room(node)
        if "/" not in node.id:
            self.ids.claim(node.id, self.name)
        self.nodes[node.id] = node
        node.serial = self._made = self._made + 1
        self._count(node, 1)
        self.journal.record(lambda: self._drop(node))
        for changes in self._recorders:
            changes.born[node.id] = None
        self.bodies.mark((node.id,))

    def _check_room(self, node: Node) -> None:
        limits, owner = self.limits, owner_of(node.id)
        if len(self.nodes) >= limits.scene_objects:
            raise LimitExceeded(f"scene {self.name} holds the maximum of "
                                f"{limits.scene_objects} objects", limit="sceneObjects",
                                value=limits.scene_objects, object=node.id)
        if self.owned[owner] >= limits.client_objects:
            raise LimitExceeded(f"{owner} has the maximum of {limits.client_objects} objects "
                                f"in scene {self.name}", limit="clientObjects",
                                value=limits.client_objects, object=node.id)
        if node.physical and self.physical >= limits.scene_bodies:
            raise LimitExceeded(f"scene {self.name} holds the maximum of {limits.scene_bodies} "
                                f"physical parts", limit="sceneBodies",
                                value=limits.scene_bodies, object=node.id)

    def _count(self, node: Node, step: int) -> None:
        owner = owner_of(node.id)
        self.owned[owner] += step
        if not self.owned[owner]:
            del self.owned[owner]
        self.physical += step if node.physical else 0

    def _drop(self, node: Node) -> None:
        del self.nodes[node.id]
        self._count(node, -1)
        self.bodies.mark((node.id,))

    def get(self, node_id: str) -> Node:
        """The node with this id, or :class:`UnknownObject`."""
        try:
            return self.nodes[node_id]
        except KeyError:
            fate = "was deleted from" if self.ids.used(node_id) and node_id.split("/")[0] \
            not in self.nodes else "is not in"
            raise UnknownObject(f"object {node_id} {fate} scene {self.name}",
                                object=node_id) from None

    def remove_client(self, client_id: str) -> list[str]:
        """A client left: its watches end, what it created and did not keep is deleted
        (newest first) and its id is never handed out again; the ids deleted at the top."""
        self.watches.drop_watcher(client_id)
        mine = [node_id for node_id, node in self.nodes.items()
                if "/" not in node_id and owner_of(node_id) == client_id and not node.is_kept()]
        deleted = []
        for object_id in reversed(mine):
            node = self.nodes.get(object_id)
            if node is not None:
                self.delete(node)
                deleted.append(object_id)
        self.ids.forget(client_id)
        return deleted

    def delete(self, node: Node) -> None:
        """Remove a node and everything below it; their ids are never used again."""
        if node.parent is not None and node in node.parent.slots:
            node.parent._drop_slot(node)
        node._link(None)
        for gone in list(node.walk()):
            self._drop(gone)
            for changes in self._recorders:
                changes.died.add(gone.id)
            self.journal.record(lambda gone=gone: self._revive(gone))

    def _revive(self, node: Node) -> None:
        self.nodes[node.id] = node
        self._count(node, 1)
        self.bodies.mark((node.id,))

    def in_order_made(self) -> list[Node]:
        """Every node in the order it was made (``nodes`` is not, once a deletion was undone)."""
        return sorted(self.nodes.values(), key=lambda node: node.serial)

    def roots(self) -> list[Node]:
        """Nodes without a parent, in the order they were made."""
        return [n for n in self.nodes.values() if n.parent is None]

    # --- change feed ---------------------------------------------------------------------

    def node_changed(self, node: Node, field: str) -> None:
        """Called by nodes after every change of their state (and of its undoing)."""
        for changes in self._recorders:
            if field in ("position", "quaternion"):
                changes.poses[node.id] = None
            elif field == "angle":
                changes.angles[node.id] = None
            else:
                changes.update(node.id, field)
        if field in _POSE_FIELDS or field == "parent":
            self._moved(node)
        if field == "visible":
            self.bodies.mark(n.id for n in node.walk())

    def turn(self, turns: list[tuple[Motor, float | None]]) -> None:
        """Motors to angles, as ``setAngle`` takes them (None and NaN ignored, the rest
        clamped: :meth:`Motor.within_limits`), journaled, reported and moving what hangs on
        them, in one pass: a robot's ``setAngles`` turns all its motors at once."""
        turns = [(motor, value) for motor, angle in turns
                 if (value := motor.within_limits(angle)) is not None and motor.angle != value]
        if not turns:
            return
        before = [(motor, motor.angle) for motor, _ in turns]
        self.journal.record(lambda: self.turn(before))
        for motor, angle in turns:
            motor.angle = angle
        for changes in self._recorders:
            changes.angles.update(dict.fromkeys(motor.id for motor, _ in turns))
        self._moved(*(motor for motor, _ in turns))

    def reparented(self, node: Node, old_parent: Node | None) -> None:
        """Called by a node that moved from ``old_parent`` to its current parent."""
        self.tree_version += 1
        parents = [parent for parent in (old_parent, node.parent) if parent is not None]
        robots = [root for root in (parent.root() for parent in parents) if isinstance(root, Robot)]
        if robots and not any(isinstance(n, Motor) for n in node.walk()):
            robots = []  # no motor moved: the robots' motor orders stand
        for changes in self._recorders:
            for parent in parents:
                changes.update(parent.id, "children")
            for robot in robots:
                changes.update(robot.id, "motors")
        self.node_changed(node, "parent")

    def _moved(self, *nodes: Node) -> None:
        self.bodies.mark([changed.id for node in nodes for changed in node.invalidate()
                          if changed.physical])

    def warn(self, message: str) -> None:
        """Tell whoever made the current request something that did not fail but may surprise."""
        for changes in self._recorders[1:]:  # the tick's own feed has no one to tell
            changes.warnings.append(message)

    @contextmanager
    def recording(self) -> Iterator[ChangeSet]:
        """Note, besides the tick's feed, what changes inside this block."""
        changes = ChangeSet()
        self._recorders.append(changes)
        try:
            yield changes
        finally:
            self._recorders.remove(changes)

    def delta(self, changes: ChangeSet) -> dict[str, Any]:
        """What a change set amounts to now, in wire form (empty parts left out)."""
        nodes, born = self.nodes, changes.born
        out: dict[str, Any] = {
            "added": [encode_numbers(nodes[i].describe()) for i in born if i in nodes],
            "angles": {i: nodes[i].angle for i in changes.angles if i in nodes and i not in born},
            "poses": {i: [*nodes[i].position, *nodes[i].quaternion] for i in changes.poses
                      if i in nodes and i not in born},
            "updates": {i: {f: _field(nodes[i], f) for f in sorted(fields)}
                        for i, fields in changes.updates.items() if i in nodes and i not in born},
            "removed": [i for i in changes.died if i not in nodes and i not in born],
        }
        if changes.camera:
            out["camera"] = {k: list(v) for k, v in self.camera.items()}
        return {k: v for k, v in out.items() if v}

    # --- time ----------------------------------------------------------------------------

    def tick(self, dt: float) -> list[dict[str, Any]]:
        """Advance the clock, place the collision bodies and return this tick's messages.

        The messages are ``added`` (new nodes), ``frame`` (always: time, sequence number
        and what changed) and ``removed``, in that order. If reading the changes fails,
        the tick raises with nothing lost: the next tick sends them. If contacts or
        sensing fail, the frame goes out without them (and the failure is logged).
        """
        delta = self.delta(self._pending)
        if self._pending:
            self.revision += 1
        self._pending.clear()
        self.time += dt
        self.seq += 1
        try:
            delta.update(self._sense())
        except Exception:  # a bug: the scene keeps running, the log tells
            self.failures += 1
            log.exception("contacts or sensing of scene %s failed", self.name)
        return frames.tick_messages(self.seq, self.time, delta)

    def _sense(self) -> dict[str, Any]:
        """This tick's contact changes, watched readings and the limits that held work back."""
        out: dict[str, Any] = {}
        bodies = self.bodies
        began, ended = bodies.contacts.update(bodies.overlaps())
        if began or ended:
            out["contacts"] = {"begin": [list(p) for p in began], "end": [list(p) for p in ended]}
        readings = self.watched_readings()
        if readings:
            out["sensors"] = {i: reading.wire() for i, reading in readings.items()}
        tracker = bodies.tracker
        out.update(frames.held_back(contactTests=tracker.deferred, contactPairs=tracker.unrecorded))
        return out

    def watched_readings(self) -> dict[str, Reading]:
        """Readings of every watched sensor (frames carry them); forgets deleted ones."""
        ids = self.watches.ids()
        self.watches.forget(i for i in ids if i not in self.nodes)
        sensors = [self.nodes[i] for i in ids if i in self.nodes]
        return self.bodies.read(sensors, exact=False)  # type: ignore[arg-type]

    @staticmethod
    def in_scene(node: Node) -> bool:
        """False for the parts of a robot taken out of the scene with ``setPosition()``."""
        root = node.root()
        return not isinstance(root, Robot) or root.visible

    def restart_feed(self) -> None:
        """Forget the changes not sent yet: every client gets a new snapshot instead
        (after the whole scene was replaced); the scene counts as changed."""
        self._pending.clear()
        self.revision += 1

    def snapshot(self) -> Snapshot:
        """The whole scene: every node (parents before children), camera, time."""
        nodes = [encode_numbers(n.describe()) for root in self.roots() for n in root.walk()]
        return Snapshot(op="snapshot", scene=self.name, seq=self.seq, time=self.time,
                        camera={k: list(v) for k, v in self.camera.items()}, nodes=nodes,
                        contacts=self.bodies.contacts.wire())

    # --- scene calls (the manual's Scene API) --------------------------------------------

    def set_camera_position(self, position: Vec3) -> None:
        """Manual ``setCameraPosition``: every viewer's camera moves there."""
        self._set_camera("position", position)

    def set_camera_target(self, target: Vec3) -> None:
        """Manual ``setCameraTarget``: every viewer's camera turns towards it."""
        self._set_camera("target", target)

    def _set_camera(self, key: str, value: Vec3) -> None:
        old = self.camera[key]
        self.journal.record(lambda: self.camera.__setitem__(key, old))
        self.camera[key] = tuple(value)
        for changes in self._recorders:
            changes.camera = True

    def set_transforms(self, transforms: list[tuple[Node, Vec3, Quat, Vec3 | None]]) -> None:
        """Place many objects at once: local position, rotation and (when given) scale
        of each (not in the manual: how a client sends what a page wrote to its objects'
        ``position``, ``quaternion`` and ``scale`` in one animation step, in one request)."""
        limit = self.limits.transforms_per_call
        if len(transforms) > limit:
            raise LimitExceeded(f"setTransforms places at most {limit} objects, got "
                                f"{len(transforms)}", limit="transformsPerCall", value=limit)
        for node, position, quaternion, scale in transforms:
            Node.set_position(node, position)  # a robot's own setPosition has more to it
            node.set_quaternion(quaternion)
            if scale is not None:
                node.set_scale(scale)

    def get_time(self) -> float:
        """Manual ``getTime()``: seconds since the scene started."""
        return self.time


def _field(node: Node, field: str) -> Any:
    if field == "parent":
        return node.parent.id if node.parent is not None else None
    if field == "children":
        return [child.id for child in node.children]
    return encode_numbers(getattr(node, field))
