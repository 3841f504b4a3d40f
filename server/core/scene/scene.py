"""The scene: one world of robots, its collision bodies, its clock and its change feed.

Sans-I/O: the web layer calls :meth:`Scene.tick` at its own rate and ships the
messages it returns; nothing here knows about sockets or event loops.
"""

from __future__ import annotations

import logging
from contextlib import AbstractContextManager
from typing import Any, Protocol

from ..kit.errors import LimitExceeded, StorageFailure
from ..kit.ids import IdBook
from ..kit.journal import Journal
from ..kit.limits import DEFAULT, Limits
from ..kit.math3d import Quat, Vec3
from ..kit.numbers import encode_numbers
from ..kit.wire_messages import Snapshot
from ..model.motor import Motor
from ..model.node import Node
from ..model.readings import Reading
from ..model.watches import Watches
from ..physics.assets import AssetLibrary, Uploads
from ..physics.settings import Physics
from . import frames
from .bodies import SceneBodies
from .camera import Camera
from .caption import Caption
from .changes import ChangeSet
from .clock import Clock
from .couplings import Couplings
from .feed import ChangeFeed
from .observations import observe, watched_readings, watched_wire
from .registry import Registry

log = logging.getLogger(__name__)
_POSE_FIELDS = ("position", "quaternion", "angle", "flipped", "scale")
_BODY_FIELDS = ("mass", "friction", "static", "following")  # a tree's body is built again with them


class RecordingControl(Protocol):
    """What records a scene: its server's process (a scene run bare has none)."""

    def start(self, client: str) -> str: ...  # a new recording's id

    def stop(self) -> dict[str, Any]: ...  # what the recording holds


class Scene:
    """Robots and parts in one PyBullet world, with time, sequence number and camera.

    The scene is what nodes know as their :class:`~server.core.model.node.World`; it ties
    together its registry of nodes, undo journal, change feed, bodies, camera and clock.
    """

    def __init__(self, name: str = "default", limits: Limits = DEFAULT,
                 assets: AssetLibrary | None = None, uploads: Uploads | None = None) -> None:
        self.name = name
        self.limits = limits
        self.journal = Journal()
        self.registry = Registry(name, limits, self.journal)
        self.nodes = self.registry.nodes
        self.assets = assets or AssetLibrary()
        self.uploads = uploads  # where a document's files not here are kept (None: refused)
        self.recorder: RecordingControl | None = None  # set by the process serving it
        self.bodies = SceneBodies(self.nodes, limits, self.assets, name)
        self.feed = ChangeFeed()
        self.camera = Camera(self.journal, lambda: self.feed.scene_changed("camera"))
        self.caption = Caption(self.journal, lambda: self.feed.scene_changed("caption"))
        self.watches = Watches(self.journal, limits.watched_sensors)
        self.time = 0.0
        self.clock = Clock(self.journal)  # running with the wall clock until a script pauses it
        self.seq = 0
        self.tree_version = 0
        self.pose_epoch = 0  # counts pose changes (Node.world_pose caches by it)
        self.revision = 0  # ticks that sent changes: a document of the scene is out of date
        self.failures = 0  # ticks whose contacts or sensing failed (a bug; logged)
        self.physics = Physics()  # kinematic until setPhysics
        # whose scene it is (server.core.protocol.ownership): none until a controller joins
        self.keeper: str | None = None
        self.moving = False  # dynamic mode: something moved in the last tick
        self.couplings = Couplings(self.nodes)
        # saveState's states (server.core.protocol.saved_states), by id; opaque here
        self.saved_states: dict[str, Any] = {}
        self.states_saved = 0
        self.restored = False  # restoreState replaced everything: the process resyncs clients

    @property
    def ids(self) -> IdBook:
        """Every id handed out in this scene, by owner."""
        return self.registry.ids

    def close(self) -> None:
        """Release the physics world."""
        self.bodies.close()

    # --- registry ------------------------------------------------------------------------

    def register(self, node: Node) -> None:
        """Add a newly made node (journaled): its id must be new to this scene."""
        self.registry.admit(node)
        self.journal.record(lambda: self._drop(node))
        self.feed.born(node.id)
        self.bodies.restructure((node.id,))

    def _drop(self, node: Node) -> None:
        self.registry.drop(node)
        self.bodies.restructure((node.id,))

    def get(self, node_id: str) -> Node:
        """The node with this id, or :class:`UnknownObject`."""
        return self.registry.get(node_id)

    def remove_client(self, client_id: str) -> list[str]:
        """A client left: its watches end, what it created and did not keep is deleted
        (newest first) and its id is never handed out again; the ids deleted at the top."""
        self.watches.drop_watcher(client_id)
        self.clock.released(client_id)
        deleted = []
        for node in reversed(self.registry.left_behind(client_id)):
            if node.id in self.nodes:  # not deleted with a part it hung on
                self.delete(node)
                deleted.append(node.id)
        self.ids.forget(client_id)
        return deleted

    def delete(self, node: Node) -> None:
        """Remove a node and everything below it; their ids are never used again."""
        if node.parent is not None and node in node.parent.slots:
            node.parent._drop_slot(node)
        node._link(None)
        for gone in list(node.walk()):
            self._drop(gone)
            self.feed.died(gone.id)
            self.journal.record(lambda gone=gone: self._revive(gone))

    def _revive(self, node: Node) -> None:
        self.registry.revive(node)
        self.bodies.restructure((node.id,))

    def in_order_made(self) -> list[Node]:
        """Every node in the order it was made (``nodes`` is not, once a deletion was undone)."""
        return self.registry.in_order_made()

    def roots(self) -> list[Node]:
        """Nodes without a parent."""
        return self.registry.roots()

    # --- change feed ---------------------------------------------------------------------

    def node_changed(self, node: Node, field: str) -> None:
        """Called by nodes after every change of their state (and of its undoing)."""
        self.feed.changed(node.id, field)
        if field in _POSE_FIELDS or field in ("parent", "visible"):
            self._moved()
            if field in ("position", "quaternion") and node.parent is None:
                self.bodies.rebased(node.id, field)
            elif field != "parent":  # reparented() names both trees
                self.bodies.restructure((node.root().id,))
        elif field in _BODY_FIELDS:
            self.bodies.restructure((node.root().id,))
            if field == "following":  # followers are kept with their trees (bodies._follow)
                self.couplings.changed()
        elif field in ("max_torque", "max_speed"):
            self.bodies.retargeted()

    def turn(self, turns: list[tuple[Motor, float | None]], coupled: bool = True) -> None:
        """Motors to angles, as ``setAngle`` takes them (None and NaN ignored, the rest
        clamped: :meth:`Motor.within_limits`), journaled, reported and moving what hangs on
        them, in one pass: a robot's ``setAngles`` turns all its motors at once. Followers
        turn with their leaders (:mod:`.couplings`) unless ``coupled`` is false."""
        if coupled:
            turns = self.couplings.expand(turns, self.tree_version)
        if self.physics.dynamic:
            self._retarget(turns)
            return
        turns = [(motor, value) for motor, angle in turns
                 if (value := motor.within_limits(angle)) is not None and motor.angle != value]
        if not turns:
            return
        before = [(motor, motor.angle) for motor, _ in turns]
        self.journal.record(lambda: self.turn(before, coupled=False))
        ids = []
        for motor, angle in turns:
            motor.angle = motor.target = angle
            ids.append(motor.id)
        self.feed.turned(ids)
        self.bodies.turned(ids)
        self._moved()

    def _retarget(self, turns: list[tuple[Motor, float | None]]) -> None:
        """Dynamic mode's turn: the motors' targets (journaled); they drive there in the
        ticks to come, and their angles are where the physics takes them."""
        turns = [(motor, value) for motor, angle in turns
                 if (value := motor.within_limits(angle)) is not None and motor.target != value]
        if not turns:
            return
        before = [(motor, motor.target) for motor, _ in turns]
        self.journal.record(lambda: self._retarget(before))
        for motor, target in turns:
            motor.target = target
        self.bodies.retargeted()

    def set_physics(self, mode: str, options: dict[str, Any] | None = None) -> None:
        """``setPhysics(mode, options)`` (not in the manual): kinematic, as 1.0 (motors jump
        to their angles, nothing falls), or dynamic (:mod:`server.core.physics.dynamics`);
        every tree is built again, at rest where it is, with motors aiming where they are."""
        physics = Physics.of(mode, options)
        if physics == self.physics:
            return
        before = self.physics
        self.journal.record(lambda: self._put_physics(before))
        self._put_physics(physics)

    def _put_physics(self, physics: Physics) -> None:
        self.physics = physics
        if not physics.dynamic:  # kinematic: motors are where they are set
            aims = [(n, n.target) for n in self.nodes.values() if n.is_motor]  # type: ignore[attr-defined]
            self.journal.record(lambda: [setattr(motor, "target", aim) for motor, aim in aims])
            for motor, _ in aims:
                motor.target = motor.angle  # type: ignore[attr-defined]
        self.bodies.remake(physics)
        self.feed.scene_changed("physics")
        self.moving = physics.dynamic

    def get_physics(self) -> dict[str, Any]:
        """``getPhysics()``: the mode and the options (as ``setPhysics`` takes them)."""
        return self.physics.wire()

    def reparented(self, node: Node, old_parent: Node | None) -> None:
        """Called by a node that moved from ``old_parent`` to its current parent."""
        self.tree_version += 1
        parents = [parent for parent in (old_parent, node.parent) if parent is not None]
        robots = [root.id for root in (parent.root() for parent in parents) if root.lists_motors]
        motors = [n.id for n in node.walk() if n.is_motor]
        if not motors:
            robots = []  # no motor moved: the robots' motor orders stand
        self.feed.regrouped([parent.id for parent in parents], robots)
        self.feed.turned(motors)  # their angles go where they went (frames._angles)
        # a node that was a root had a tree of its own: it goes too (else its body stayed
        # where it was, a ghost that touched things, beside the tree it joined)
        was_root = [node.id] if old_parent is None else []
        self.bodies.restructure({node.root().id, *was_root, *(parent.root().id for parent in parents)})
        self.node_changed(node, "parent")

    def _moved(self) -> None:
        """Poses changed: every world pose cached for reads is stale."""
        self.pose_epoch += 1

    def warn(self, message: str) -> None:
        """Tell whoever made the current request something that did not fail but may surprise."""
        self.feed.warn(message)

    def recording(self) -> AbstractContextManager[ChangeSet]:
        """Note, besides the tick's feed, what changes inside this block."""
        return self.feed.recording()

    def delta(self, changes: ChangeSet) -> dict[str, Any]:
        """What a change set amounts to now, in wire form (empty parts left out)."""
        # scene-level fields' wire forms only when they changed: every tick's delta asks
        return frames.changes_wire(self.nodes, changes, {
            field: self._scene_field(field) for field in changes.scene})

    def _scene_field(self, field: str) -> Any:
        if field == "camera":
            return self.camera.wire()
        return self.physics.wire() if field == "physics" else self.caption.text

    # --- time ----------------------------------------------------------------------------

    def tick(self, dt: float) -> list[dict[str, Any]]:
        """Advance the clock, place the collision bodies and return this tick's messages.

        The messages are ``added`` (new nodes), ``frame`` (always: time, sequence number
        and what changed) and ``removed``, in that order. If reading the changes fails,
        the tick raises with nothing lost: the next tick sends them. If contacts or
        sensing fail, the frame goes out without them (and the failure is logged). A big
        batch of new parts gets its bodies over several ticks (:mod:`.build_stages`).
        """
        with self.bodies.stages.tick():
            return self._tick(dt)

    def stand(self) -> list[dict[str, Any]]:
        """A paused dynamic scene's frame of no time: what requests changed reaches every
        client, but the world is neither built, stepped nor sensed until the next step.
        Stands come when the wall clock says: a body built or sensed in one (a hand half
        made between two of its script's messages) made the same seeded grasp end
        differently on a loaded machine (5 of 8 held instead of 7). Not paused or not
        dynamic: an ordinary tick of no time."""
        if not (self.clock.paused and self.physics.dynamic):
            return self.tick(0.0)
        return self._tick(0.0, standing=True)

    def _tick(self, dt: float, standing: bool = False) -> list[dict[str, Any]]:
        # the clock is the world's: a late tick slows it, never jumps
        if self.physics.dynamic and not standing:
            dt = self._step(dt)
        pending = self.feed.pending
        delta = self.delta(pending)
        if pending:
            self.revision += 1
        pending.clear()
        self.time += dt
        self.seq += 1
        try:
            if not standing:
                delta.update(observe(self.bodies, self.watches, self.nodes))
        except Exception:  # a bug: the scene keeps running, the log tells
            self.failures += 1
            log.exception("contacts or sensing of scene %s failed", self.name)
        return frames.tick_messages(self.seq, self.time, delta)

    def _step(self, dt: float) -> float:
        """Dynamic mode: advance the physics through ``dt`` and take where it put every
        motor and free body (not journaled: it is the world's doing, not a request's); the
        seconds it went through."""
        # a paused scene ticks when its script steps it: exactly, whatever the machine's load
        seconds, angles, poses = self.bodies.advance(dt, exact=self.clock.paused_by is not None)
        for motor_id, angle in angles.items():
            self.nodes[motor_id].angle = angle  # type: ignore[attr-defined]
        for root_id, (position, quaternion) in poses.items():
            root = self.nodes[root_id]
            root.position, root.quaternion = position, quaternion
            self.feed.changed(root_id, "position")
        self.feed.turned(angles)
        self.moving = bool(angles or poses)
        if self.moving:
            self._moved()
        return seconds

    def watched_readings(self) -> dict[str, Reading]:
        """Readings of every watched sensor (frames carry them); forgets deleted ones."""
        return watched_readings(self.bodies, self.watches, self.nodes)

    def restart_feed(self) -> None:
        """Forget the changes not sent yet: every client gets a new snapshot instead
        (after the whole scene was replaced); the scene counts as changed."""
        self.feed.pending.clear()
        self.revision += 1

    def snapshot(self) -> Snapshot:
        """The whole scene: every node (parents before children), camera, time, the pairs
        touching, (dynamic mode) the forces pressing and the watched sensors' readings."""
        nodes = [encode_numbers(n.describe()) for root in self.roots() for n in root.walk()]
        snapshot = Snapshot(op="snapshot", scene=self.name, seq=self.seq, time=self.time,
                            camera=self.camera.wire(), physics=self.physics.wire(), nodes=nodes,
                            contacts=self.bodies.contacts.wire())
        if self.caption.text:
            snapshot["caption"] = self.caption.text
        forces = self.bodies.forces.told()
        if forces:
            snapshot["forces"] = forces
        readings = watched_wire(self.bodies, self.watches, self.nodes)
        if readings:
            snapshot["sensors"] = readings
        return snapshot

    # --- scene calls (the manual's Scene API) --------------------------------------------

    def set_camera_position(self, position: Vec3) -> None:
        """Manual ``setCameraPosition``: every viewer's camera moves there."""
        self.camera.set("position", position)

    def set_camera_target(self, target: Vec3) -> None:
        """Manual ``setCameraTarget``: every viewer's camera turns towards it."""
        self.camera.set("target", target)

    def set_caption(self, text: str) -> None:
        """``setCaption(text)`` (not in the manual): every viewer shows ``text`` in a corner
        ("" hides it)."""
        self.caption.set(text)

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

    def pause(self, client: str) -> None:
        """``pause()`` (not in the manual): the scene's clock stands until ``resume`` (or
        until the client that paused it leaves); ``step`` advances it (:mod:`.clock`)."""
        self.clock.pause(client)

    def resume(self) -> None:
        """``resume()``: the scene's clock runs with the wall clock again."""
        self.clock.resume()

    def step(self, ticks: int) -> None:
        """``step(ticks)``: advance a paused scene by whole ticks, taken before the answer."""
        self.clock.step(ticks)

    def start_recording(self, client: str) -> str:
        """``startRecording()`` (not in the manual): the server records the scene from now
        (server.core.recording); the recording's id."""
        return self._recorder().start(client)

    def stop_recording(self) -> dict[str, Any]:
        """``stopRecording()``: the recording stops; what it holds."""
        return self._recorder().stop()

    def _recorder(self) -> RecordingControl:
        if self.recorder is None:
            raise StorageFailure("this scene keeps no recordings: it runs outside a server")
        return self.recorder

