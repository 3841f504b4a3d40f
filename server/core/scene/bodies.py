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

if TYPE_CHECKING:
    from ..kit.math3d import Pose
    from ..physics.articulation import Articulation

log = logging.getLogger(__name__)
# How a sync builds the trees not built before: as this tick's build stage admits them
# (dynamic mode), all of them, or none (left for a later sync)
STAGED, ALL, LATER = "staged", "all", "later"
HAIR = 1e-9  # dynamic mode: a joint or body that moved less than this (m, rad) has not moved
_ANGLE = attrgetter("angle")


def _apart(a: Pose, b: Pose) -> bool:
    return any(abs(x - y) > HAIR for x, y in zip((*a[0], *a[1]), (*b[0], *b[1])))


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
        self.tracker = ContactTracker(self.physics, limits.contact_tests, limits.contact_pairs)
        self.contacts = ContactBook()  # as announced by the last tick
        self._restructured: set[str] = set()  # roots (then) whose trees are built again
        self._unchecked: set[str] = set()  # of those, the roots not yet checked (check_trees)
        self._based: dict[str, set[str]] = {}  # roots whose own pose changed -> which fields
        self._turned: set[str] = set()        # motors whose angles changed
        self._motor_root: dict[str, str] = {}  # motor id -> root of the tree it is a joint of
        self._joint_motors: dict[str, list[Node]] = {}  # root -> its joints' motors, in order
        self._followers: dict[str, list[Node]] = {}  # root -> its motors that follow another
        self._ray_geometry: dict[str, dict[str, Any]] = {}
        self._parts = Carriers()  # the parts with bodies; what they carry
        self._unposed: set[str] = set()  # roots moved since their parts' poses were read
        self.failures = 0  # trees that could not be built or placed (a bug; logged)
        self._targets_due = False  # dynamic mode: motors' targets to be driven toward
        self._forces_sent: dict[str, float] = {}  # by the last frame (forces_changed)
        self._stirred = True  # anything built, put or moved since contacts were read
        # dynamic mode: anything built, put or driven since steps were last taken (its own
        # flag: a tick that took no step, its time too short or a paused scene's stand,
        # read the contacts and so cleared the one above, and a still world then counted
        # every later step as rest: a ball put up high in it hung there)
        self._changed = True
        self._still = False  # dynamic mode: the last steps moved nothing
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
        self._targets_due = True

    def _follow(self) -> None:
        """Dynamic mode: each follower aims at its share of where its leader really is (a
        finger whose first joint an object stops stops curling, as a linkage does; Bullet's
        own gear constraint was tried and measured wrong on a robot's floating base)."""
        for followers in self._followers.values():
            for follower in followers:
                leader = follower.leader()  # type: ignore[attr-defined]
                if leader is None:
                    continue
                aim = follower.share_of(leader.angle)  # type: ignore[attr-defined]
                if aim is not None and aim != follower.target:  # type: ignore[attr-defined]
                    follower.target = aim  # type: ignore[attr-defined]
                    self._targets_due = True

    def turned(self, motor_ids: Iterable[str]) -> None:
        """Motors turned: their joints are set at the next sync."""
        self._turned.update(motor_ids)

    # --- keeping bodies in step ------------------------------------------------------------

    def sync(self, new_trees: str = STAGED) -> None:
        """Build, place and turn what changed; then read the moved parts' poses.
        ``new_trees``: how trees not built before are built (:data:`STAGED`)."""
        if not (self._restructured or self._based or self._turned):
            return
        self._stirred = self._changed = True
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
        self._targets_due = physics.dynamic
        self._stirred = self._changed = True

    def advance(self, dt: float, exact: bool = False) -> tuple[float, dict[str, float], dict[str, Pose]]:
        """Dynamic mode: drive the motors, step the world through ``dt``; the seconds the
        world went through (less than ``dt`` when it is behind), the motors' new angles and
        the free roots' new poses (what moved more than a hair). ``exact``: every step,
        whatever it costs (a script steps the scene: Dynamics.advance)."""
        self.sync()
        physics = self.physics
        if self._followers:
            self._follow()
        if self._targets_due:
            for root_id, motors in self._joint_motors.items():
                physics.drive(root_id, [m.target for m in motors],  # type: ignore[attr-defined]
                              [m.get_max_torque() for m in motors],  # type: ignore[attr-defined]
                              [m.get_max_speed() for m in motors])  # type: ignore[attr-defined]
            self._targets_due = False
            self._stirred = self._changed = True
        dynamics = physics.dynamics
        at_rest = self._still and not self._changed
        steps = dynamics.advance(dt, still=at_rest, exact=exact)  # type: ignore[union-attr]
        if not steps or at_rest:
            return steps * dynamics.physics.step, {}, {}  # type: ignore[union-attr]
        self._changed = False
        angles: dict[str, float] = {}
        poses: dict[str, Pose] = {}
        for root_id, pose, joints in physics.motions():
            moved = False
            for motor, angle in zip(self._joint_motors.get(root_id, ()), joints):
                if abs(motor.angle - angle) > HAIR:  # type: ignore[attr-defined]
                    angles[motor.id] = angle
                    moved = True
            if pose is not None and _apart(self._nodes[root_id].local_pose(), pose):
                poses[root_id] = pose
                moved = True
            if moved:
                self.tracker.moved(physics.tree(root_id).parts())  # type: ignore[union-attr]
                self._unposed.add(root_id)
        self._still = not (angles or poses or dynamics.woke)  # type: ignore[union-attr]
        self._stirred = self._stirred or not self._still
        return steps * dynamics.physics.step, angles, poses  # type: ignore[union-attr]

    def forces_changed(self) -> dict[str, float]:
        """Newtons on each part whose force changed since the last call (0: it ended),
        rounded to 1 mN, as frames carry them (none in kinematic mode)."""
        now = {key: round(force, 3) for key, force in self.physics.forces.items()}
        changed = {key: force for key, force in now.items() if self._forces_sent.get(key) != force}
        changed.update((key, 0.0) for key in self._forces_sent if key not in now)
        self._forces_sent = {key: force for key, force in now.items() if force}
        return changed

    def forces_told(self) -> dict[str, float]:
        """Newtons on each pressed part as the frames sent so far have told them: what a
        snapshot gives a newcomer, so that a force that stopped changing is still known."""
        return dict(self._forces_sent)

    def peak_force(self) -> float:
        """The most newtons pressing on any one part at the last tick (0 in kinematic mode)."""
        return max(self.physics.forces.values(), default=0.0)

    def force_on(self, part: Node | None) -> float:
        """Newtons pressing on ``part`` at the last tick (0 in kinematic mode)."""
        return 0.0 if part is None else self.physics.forces.get(part.id, 0.0)

    def motor_motion(self, motors: Sequence[Node]) -> list[tuple[float, float]]:
        """Each motor's speed (rad/s; a slider's, scene units/s) and the torque (a slider's
        force) it drove with in the last step, N·m (N), positive turning its angle up; 0, 0
        in kinematic mode, where motors jump to their angles, and for a motor not yet
        built into its tree."""
        self.sync()
        out = []
        read: dict[str, tuple[list[float], list[float]]] = {}
        for motor in motors:
            root_id = motor.root().id
            built = self._joint_motors.get(root_id, [])
            if self.physics.dynamics is None or motor not in built:
                out.append((0.0, 0.0))
                continue
            if root_id not in read:  # one read of Bullet per tree
                read[root_id] = self.physics.joint_motion(root_id)
            speeds, efforts = read[root_id]
            index = built.index(motor)
            out.append((speeds[index], efforts[index]))
        return out

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
        self._followers.pop(root_id, None)

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
            self.physics.add_tree(tree, base_pose(node), angles, self._mount_of(node))
        except Exception:  # a bug: this tree is left out, the scene goes on
            self.failures += 1
            log.exception("the parts of %s in scene %s could not be placed", root_id, self._name)
            return []
        self._motor_root.update(dict.fromkeys(angles, root_id))
        self._joint_motors[root_id] = [self._nodes[motor] for motor in angles]
        followers = [m for m in self._joint_motors[root_id] if m.following is not None]  # type: ignore[attr-defined]
        if followers:
            self._followers[root_id] = followers
        else:
            self._followers.pop(root_id, None)
        if self.physics.dynamics is not None:
            self._targets_due = True
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
            if self._guarded(root_id, lambda: self._move_base(root_id, node, fields)):
                placed.add(root_id)
        self._based.clear()
        return placed

    def _move_base(self, root_id: str, node: Node, fields: set[str]) -> None:
        """Put a root's base where its node is. A dynamic robot's node carries where the
        physics put it (a loaded hand turns a little at its mount): what the script did not
        set keeps its mount's value, or a held weight would tip the hand further at every
        setPosition."""
        pose = base_pose(node)
        if self.physics.dynamics is None or not node.lists_motors:
            self.physics.move_base(root_id, pose)
            return
        mount = self._mount_of(node) or pose
        pose = (pose[0] if "position" in fields else mount[0],
                pose[1] if "quaternion" in fields else mount[1])
        self.physics.move_base(root_id, pose)
        node.mount = pose  # type: ignore[attr-defined]

    def _mount_of(self, node: Node) -> Pose | None:
        """Dynamic mode: where a robot's mount holds it; the first time it is built in a
        dynamic world, where its node is (so a script that puts it where it is, tick after
        tick, holds it as one that does not: its node turned with the physics, and the
        first put turned the mount to that). None: not a robot, or kinematic mode."""
        if self.physics.dynamics is None or not node.lists_motors:
            return None
        if node.mount is None:  # type: ignore[attr-defined]
            node.mount = base_pose(node)  # type: ignore[attr-defined]
        return node.mount  # type: ignore[attr-defined,no-any-return]

    def hold_mounts(self) -> None:
        """Dynamic mode: every built robot's mount put at once where its node's mount is:
        where a document restored it (after its tree was built where its node is), or
        where the robot is, for one moved into a new world (a mount first set at the next
        setPosition took the turn the physics had given the node by then, and a script's
        hand went one way or another as that came a tick sooner or later)."""
        for root_id in self.physics.roots():
            node = self._nodes.get(root_id)
            mount = None if node is None else self._mount_of(node)
            if mount is not None:
                self.physics.place_mount(root_id, mount)

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
        pressing = self.physics.contacts({host for host in ids if host is not None})
        return read_sensors(self._rays, sensors, contacts,
                            [pressing.get(host, ()) for host in ids] if pressing else None,
                            *self.world_frames(sensors))
