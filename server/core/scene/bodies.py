"""The physical side of a scene: bodies and ray shapes of its parts, contacts and sensing.

Every tree of nodes with a physical part in the scene is one multibody in the engine
(:mod:`server.core.model.structure` compiles it; motors are its joints), and every
physical part has a ray shape (:mod:`server.core.physics.raycast`) at its world pose. The
scene says what changed: a tree's structure (built again, one call), a root's pose (its
base is placed) or motors' angles (all of a tree's joints set in one call). :meth:`sync`
brings the engine in step before anything is measured, and reads the parts' world poses
from Bullet's forward kinematics, one call per tree. PyBullet never moves anything by
itself (kinematic mode, as 1.0).
"""

from __future__ import annotations

import logging
from operator import attrgetter
from typing import TYPE_CHECKING, Any, Callable, Iterable, Mapping, Sequence

import numpy as np

from ..kit.errors import LimitExceeded
from ..kit.limits import Limits
from ..model.node import Node
from ..model.readings import Reading, read_sensors
from ..model.structure import base_pose, structure_of
from ..physics.articulation import check_links
from ..physics.assets import AssetLibrary
from ..physics.contacts import ContactBook, ContactTracker, Overlaps
from ..physics.engine import PhysicsWorld
from ..physics.raycast import RayTargets
from ..physics.settings import Physics
from .build_stages import BuildStages
from .carriers import Carriers
from .mounts import hold_mounts, mount_of, move_base
from .part_forces import PartForces
from .stepping import Stepping

if TYPE_CHECKING:
    from ..kit.math3d import Pose
    from ..physics.articulation import Articulation

log = logging.getLogger(__name__)
# How a sync builds the trees not built before: as this tick's build stage admits them
# (dynamic mode), all of them, or none (left for a later sync)
STAGED, ALL, LATER = "staged", "all", "later"
_ANGLE = attrgetter("angle")


class SceneBodies:
    """Multibodies and ray shapes of the physical parts of one scene's nodes.

    Only parts that are :meth:`~server.core.model.node.Node.in_scene` have bodies (a robot
    taken out of the scene keeps its parts, without bodies).
    """

    def __init__(self, nodes: Mapping[str, Node], limits: Limits, assets: AssetLibrary,
                 name: str = "") -> None:
        self._nodes = nodes
        self._name = name
        self.physics = PhysicsWorld()
        self._rays = RayTargets(assets)
        self.tracker = ContactTracker(self.physics.parts, limits.contact_tests, limits.contact_pairs)
        self.contacts = ContactBook()  # as announced by the last tick
        self._restructured: set[str] = set()  # roots (then) whose trees are built again
        self._unchecked: set[str] = set()  # of those, the roots not yet checked (check_trees)
        self._based: dict[str, set[str]] = {}  # roots whose own pose changed -> which fields
        self._turned: set[str] = set()        # motors whose angles changed
        self._motor_root: dict[str, str] = {}  # motor id -> root of the tree it is a joint of
        self._joint_motors: dict[str, list[Node]] = {}  # root -> its joints' motors, in order
        self._ray_geometry: dict[str, dict[str, Any]] = {}
        self._parts = Carriers()  # the parts with bodies; what they carry
        self._unposed: set[str] = set()  # roots moved since their parts' poses were read
        self.failures = 0  # trees that could not be built or placed (a bug; logged)
        self._stirred = True  # anything built, put or moved since contacts were read
        self.stepping = Stepping(self.physics, nodes, self._joint_motors)  # dynamic mode
        self.forces = PartForces(self.physics.parts)  # dynamic mode: what presses on parts
        self.stages = BuildStages()  # how many new trees a tick builds

    @property
    def rays(self) -> RayTargets:
        """The ray shapes of the parts, at their poses now."""
        self._read_poses()
        return self._rays

    def close(self) -> None:
        """Release the physics world."""
        self.physics.close()

    def __len__(self) -> int:
        return len(self.physics)

    # --- what changed ----------------------------------------------------------------------

    def restructure(self, root_ids: Iterable[str]) -> None:
        """The trees of these roots changed shape (a node made, deleted, attached, scaled,
        shown, flipped, or moved below its root): built again at the next sync."""
        self._restructured.update(root_ids)
        self._unchecked.update(root_ids)

    def check_trees(self) -> None:
        """Refuse (``limit_exceeded``) a tree changed since the last check that the engine
        could not hold: called before a request's changes are kept, so that it changes
        nothing, rather than at the sync, which could only leave the tree out. (Only those
        changed since: a text of a thousand creates and attaches checked every root made
        since the last tick at every request, 2 s of structures for 300 parts.)"""
        unchecked, self._unchecked = self._unchecked, set()
        for root_id in unchecked:
            node = self._nodes.get(root_id)
            if node is not None and node.parent is None:
                try:
                    check_links(root_id, len(structure_of(node).links))
                except LimitExceeded:
                    self._unchecked.update(unchecked)  # (the request is undone: again next time)
                    raise

    def rebased(self, root_id: str, field: str) -> None:
        """A root's ``position`` or ``quaternion`` was set: its base is placed at the next sync."""
        self._based.setdefault(root_id, set()).add(field)

    def retargeted(self) -> None:
        """Dynamic mode: motors got new targets (or torques), driven from the next step."""
        self.stepping.targets_due = True

    def turned(self, motor_ids: Iterable[str]) -> None:
        """Motors turned: their joints are set at the next sync."""
        self._turned.update(motor_ids)

    # --- keeping bodies in step ------------------------------------------------------------

    def sync(self, new_trees: str = STAGED) -> None:
        """Build, place and turn what changed; then read the moved parts' poses.
        ``new_trees``: how trees not built before are built (:data:`STAGED`)."""
        if not (self._restructured or self._based or self._turned):
            return
        self._stirred = self.stepping.changed = True
        rebuilt = self._rebuild(new_trees)
        moved = self._turn(rebuilt) | self._place_bases(rebuilt)
        for root_id in moved:
            self.tracker.moved(self.physics.tree(root_id).parts())  # type: ignore[union-attr]
        self._unposed.update(moved)
        if self.physics.needs_rebuild():
            self.physics.rebuild()
            self.tracker.made_again()

    # --- dynamic mode ------------------------------------------------------------------

    def remake(self, physics: Physics) -> None:
        """Every tree built again, at rest where it is, in a world of ``physics``."""
        staged = self.physics.dynamics is not None
        # trees not built yet are built once, in the new world, not in this one and moved
        # (an import makes every tree anew: a restore built each three times, now once)
        self.sync(new_trees=LATER)
        for node in self._nodes.values():  # (held again where they are, at rest)
            if node.lists_motors:
                node.mount = None  # type: ignore[attr-defined]
        self.physics.rebuild(physics)
        self.tracker.crowding = not physics.dynamic
        self.tracker.made_again()
        self._unposed.update(self.physics.roots())
        self.sync(new_trees=STAGED if staged else ALL)  # as the old world would have built them
        self.hold_mounts()  # (those moved from the old world, too: held from their first step)
        self.stepping.targets_due = physics.dynamic
        self._stirred = self.stepping.changed = True

    def advance(self, dt: float, exact: bool = False) -> tuple[float, dict[str, float], dict[str, Pose]]:
        """Dynamic mode: drive the motors, step the world through ``dt`` (:mod:`.stepping`);
        the seconds the world went through, the motors' new angles and the free roots' new
        poses. ``exact``: every step, whatever it costs (a script steps the scene)."""
        self.sync()
        steps = self.stepping.advance(dt, exact)
        for root_id in steps.moved:
            self.tracker.moved(self.physics.tree(root_id).parts())  # type: ignore[union-attr]
            self._unposed.add(root_id)
        self._stirred = self._stirred or steps.stirred
        return steps.seconds, steps.angles, steps.poses

    def motor_motion(self, motors: Sequence[Node]) -> list[tuple[float, float]]:
        """Each motor's speed and the torque it drove with in the last step
        (:meth:`.Stepping.motor_motion`)."""
        self.sync()
        return self.stepping.motor_motion(motors)

    def _read_poses(self) -> None:
        """Read the parts' poses of the trees moved since they were last read (Bullet's
        forward kinematics, a call per tree): only rays and sensors need them, so a tick
        that senses nothing reads none."""
        self.sync()
        tree, poses = self.physics.tree, self.physics.part_pose_rows
        self._rays.place_trees([poses(root_id) for root_id in self._unposed
                                if tree(root_id) is not None])  # (not since taken out)
        self._unposed.clear()

    def _rebuild(self, new_trees: str) -> set[str]:
        """Build the marked trees again; the roots built."""
        roots: set[str] = set()
        for root_id in self._restructured:
            node = self._nodes.get(root_id)
            roots.add(root_id)
            if node is not None and node.parent is not None:
                roots.add(node.root().id)  # attached below another tree since
        self._restructured.clear()
        # in the order the roots were made, not a set's: Bullet's solver visits bodies in
        # the order they were added, and the same script must give the same world
        order = sorted(roots, key=lambda root_id: getattr(self._nodes.get(root_id), "serial", 0))
        old: set[str] = set()
        had: set[str] = set()  # roots with a tree: built again now, whatever the stage
        for root_id in order:  # every old tree out first: a part may change trees
            tree = self.physics.tree(root_id)
            if tree is not None:
                old.update(tree.parts())
                had.add(root_id)
                self._forget_tree(root_id, tree)
        new: set[str] = set()
        waiting = self._waiting([root_id for root_id in order if root_id not in had], new_trees)
        self._restructured.update(waiting)
        built = [root_id for root_id in order if root_id not in waiting] if waiting else order
        if built:
            self._parts.forget_offsets()  # and what it held of nodes deleted since
        for root_id in built:
            new.update(self._build(root_id))
        self._forget_parts(old - new)
        return set(built)

    def _waiting(self, new_roots: list[str], new_trees: str) -> set[str]:
        """Of the roots to be built anew, in order, those this tick's stage leaves for a
        later one (:mod:`.build_stages`; dynamic mode only: a kinematic world has no
        solver, and its recordings resimulate exactly from a snapshot, every body built)."""
        if new_trees == LATER:
            return set(new_roots)
        if new_trees == ALL or self.physics.dynamics is None:
            return set()
        world = len(self.physics)
        for index, root_id in enumerate(new_roots):
            node = self._nodes.get(root_id)
            parts = 0 if node is None else sum(1 for _ in node.walk())  # (motors count too)
            if not self.stages.admits(parts, world):
                return set(new_roots[index:])
            world += parts
        return set()

    def _forget_parts(self, keys: Iterable[str]) -> None:
        """Parts without a body any more: their contacts end, their ray shapes go, and
        nothing is carried by them."""
        keys = list(keys)
        self._parts.forget(keys)
        for key in keys:
            self.tracker.removed(key)
            self._rays.remove(key)
            del self._ray_geometry[key]

    def _forget_tree(self, root_id: str, tree: Articulation) -> None:
        self.physics.remove_tree(root_id)
        for _, joint in tree.joints():
            self._motor_root.pop(joint.motor, None)
        self._joint_motors.pop(root_id, None)
        self.stepping.forgot(root_id)

    def _build(self, root_id: str) -> list[str]:
        """Build the tree of a root (nothing for a node gone, attached or without parts)."""
        node = self._nodes.get(root_id)
        if node is None or node.parent is not None:
            return []
        try:
            tree = structure_of(node)
            if not tree.parts():
                return []
            angles = {joint.motor: self._nodes[joint.motor].angle for _, joint in tree.joints()}
            self.physics.add_tree(tree, base_pose(node), angles, mount_of(self.physics, node))
        except Exception:  # a bug: this tree is left out, the scene goes on
            self.failures += 1
            log.exception("the parts of %s in scene %s could not be placed", root_id, self._name)
            return []
        self._motor_root.update(dict.fromkeys(angles, root_id))
        self._joint_motors[root_id] = [self._nodes[motor] for motor in angles]
        self.stepping.built(root_id, self._joint_motors[root_id])
        keys, poses = self.physics.part_poses(root_id)
        geometries = {tree.base_part: tree.base_geometry,
                      **{link.part: link.geometry for link in tree.links}}
        for key, pose in zip(keys, poses):
            geometry = geometries[key]
            if self._ray_geometry.get(key) != geometry:
                if key in self._ray_geometry:
                    self._rays.remove(key)
                self._rays.add(key, geometry, pose)
                self._ray_geometry[key] = geometry
            else:
                self._rays.move(key, pose)
        self.tracker.placed(keys, made=True)
        self._parts.built(keys, self.physics.tree(root_id).scales())  # type: ignore[union-attr]
        return keys

    def world_frames(self, nodes: list[Node]) -> tuple[np.ndarray, np.ndarray]:
        """World positions (n×3) and rotation matrices (n×3×3) of nodes (:class:`Carriers`)."""
        self._read_poses()
        return self._parts.world_frames(nodes, self._rays.frames)

    def _guarded(self, root_id: str, work: Callable[[], None]) -> bool:
        """Do ``work`` for a tree; if it fails (a bug) the tree is left out, the scene goes on."""
        try:
            work()
            return True
        except Exception:
            self.failures += 1
            log.exception("the parts of %s in scene %s could not be placed", root_id, self._name)
            tree = self.physics.tree(root_id)
            if tree is not None:
                self._forget_tree(root_id, tree)
                self._forget_parts(tree.parts())
            return False

    def _turn(self, rebuilt: set[str]) -> set[str]:
        """Set the joints of the trees with turned motors, a call per tree; the roots turned."""
        motor_root, nodes = self._motor_root, self._nodes
        roots = set(map(motor_root.get, self._turned))
        if None in roots:  # motors that are no joint: gone, lone, or in a tree without parts
            roots.discard(None)
            for motor_id in self._turned:
                motor = nodes.get(motor_id)
                if motor_id not in motor_root and motor is not None and motor.parent is None:
                    self.rebased(motor_id, "quaternion")  # a lone motor: its turn is its base's pose
        self._turned.clear()
        motors, turn, pending = self._joint_motors, self.physics.turn, roots - rebuilt
        try:  # (every tree of a tick, one try: a failing tree is then found one by one)
            for root_id in pending:
                turn(root_id, list(map(_ANGLE, motors[root_id])))
            return pending
        except Exception:
            return {root_id for root_id in pending if self._guarded(
                root_id, lambda: turn(root_id, list(map(_ANGLE, motors[root_id]))))}

    def _place_bases(self, rebuilt: set[str]) -> set[str]:
        """Place the bases of the moved roots; the roots placed."""
        placed = set()
        for root_id, fields in self._based.items():
            node = self._nodes.get(root_id)
            if root_id in rebuilt or node is None or not self.physics.tree(root_id):
                continue
            if self._guarded(root_id, lambda: move_base(self.physics, root_id, node, fields)):
                placed.add(root_id)
        self._based.clear()
        return placed

    def hold_mounts(self) -> None:
        """Dynamic mode: every built robot's mount put where its node's mount is
        (:func:`.mounts.hold_mounts`)."""
        hold_mounts(self.physics, self._nodes)

    # --- contacts and sensors --------------------------------------------------------------

    def overlaps(self) -> Overlaps:
        """The pairs touching now, as far as one update's budget of tests measures."""
        self.sync()
        # a world where nothing was built, put or moved since touches as it did (and, in
        # dynamic mode, presses as it did: a settled heap, asleep): a still scene of 100
        # hands spent 14 ms a tick, most of a core, finding the same contacts again, and
        # Bullet's contacts of 2 000 balls are 3 ms to read
        if self._stirred or self.tracker.unsettled:
            self.tracker.update()
            self._stirred = False
        return self.tracker.overlaps()

    def touching(self, part: Node | None, exact: bool = True) -> list[str]:
        """Ids of what ``part`` touches, sorted ("ground" for the ground).

        Exact: measured now. Otherwise as of the last tick (watched readings use that).
        """
        if part is None:
            return []
        if exact:
            self.sync()
            self.tracker.settle(part.id)
        return list(self.tracker.overlaps().of(part.id))

    def read(self, sensors: list[Node], exact: bool = True) -> dict[str, Reading]:
        """Readings of ``sensors`` for the scene as it is now (their contacts: exact, or as
        of the last tick, which watched readings use)."""
        if not sensors:
            return {}
        self._read_poses()
        ids = self._parts.host_ids(sensors)
        if exact:
            contacts = [self.touching(None if host is None else self._nodes.get(host)) for host in ids]
        else:
            contacts = self.tracker.overlaps().partners_of(ids)
        pressing = self.physics.parts.contacts({host for host in ids if host is not None})
        return read_sensors(self._rays, sensors, contacts,
                            [pressing.get(host, ()) for host in ids] if pressing else None,
                            *self.world_frames(sensors))
