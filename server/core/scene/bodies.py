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
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Iterable, Mapping, Sequence

import numpy as np

from ..kit.limits import Limits
from ..kit import math3d
from ..model.node import UNIT_SCALE, Node
from ..model.readings import Reading, read_sensors
from ..model.structure import base_pose, structure_of
from ..physics.assets import AssetLibrary
from ..physics.contacts import ContactBook, ContactTracker, Overlaps
from ..physics.engine import PhysicsWorld
from ..physics.raycast import RayTargets

if TYPE_CHECKING:
    from ..kit.math3d import Pose, Vec3
    from ..physics.articulation import Articulation

log = logging.getLogger(__name__)
_CARRIED_SETS = 64  # sets of nodes whose carriers are kept (watched sensors: one set)


@dataclass(frozen=True)
class _Carried:
    """Nodes (by index in a list of them) that parts carry: the part carrying each and the
    node's offset from it; and the nodes posed by their tree instead (``own``)."""

    own: list[int]
    rows: np.ndarray
    hosts: list[str]
    positions: np.ndarray
    quats: np.ndarray


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
        self._based: set[str] = set()         # roots whose own pose changed
        self._turned: set[str] = set()        # motors whose angles changed
        self._motor_root: dict[str, str] = {}  # motor id -> root of the tree it is a joint of
        self._joint_motors: dict[str, list[Node]] = {}  # root -> its joints' motors, in order
        self._ray_geometry: dict[str, dict[str, Any]] = {}
        self._poses: dict[str, Pose] = {}  # of every part, as Bullet placed it at the last sync
        self._scales: dict[str, Vec3] = {}  # and its world scale
        # node id -> the part carrying it and its offset from it (None: none); until a build
        self._offsets: dict[str, tuple[str, Pose] | None] = {}
        self._unposed: set[str] = set()  # roots moved since their parts' poses were read
        self._carried: dict[tuple[str, ...], _Carried] = {}  # node ids -> as world_poses needs
        self.failures = 0  # trees that could not be built or placed (a bug; logged)

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

    def rebased(self, root_id: str) -> None:
        """A root moved: its base is placed at the next sync."""
        self._based.add(root_id)

    def turned(self, motor_ids: Iterable[str]) -> None:
        """Motors turned: their joints are set at the next sync."""
        self._turned.update(motor_ids)

    # --- keeping bodies in step ------------------------------------------------------------

    def sync(self) -> None:
        """Build, place and turn what changed; then read the moved parts' poses."""
        if not (self._restructured or self._based or self._turned):
            return
        rebuilt = self._rebuild()
        moved = self._turn(rebuilt) | self._place_bases(rebuilt)
        for root_id in moved:
            self.tracker.moved(self.physics.tree(root_id).parts())  # type: ignore[union-attr]
        self._unposed.update(moved)
        if self.physics.needs_rebuild():
            self.physics.rebuild()
            self.tracker.made_again()

    def _read_poses(self) -> None:
        """Read the parts' poses of the trees moved since they were last read (Bullet's
        forward kinematics, a call per tree): only rays and sensors need them, so a tick
        that senses nothing reads none."""
        self.sync()
        for root_id in self._unposed:
            if self.physics.tree(root_id) is not None:  # (not since taken out)
                keys, poses = self.physics.part_poses(root_id)
                self._rays.move_many(keys, poses)
                self._poses.update(zip(keys, poses))
        self._unposed.clear()

    def _rebuild(self) -> set[str]:
        """Build the marked trees again; the roots built."""
        roots: set[str] = set()
        for root_id in self._restructured:
            node = self._nodes.get(root_id)
            roots.add(root_id)
            if node is not None and node.parent is not None:
                roots.add(node.root().id)  # attached below another tree since
        self._restructured.clear()
        old: set[str] = set()
        for root_id in roots:  # every old tree out first: a part may change trees
            tree = self.physics.tree(root_id)
            if tree is not None:
                old.update(tree.parts())
                self._forget_tree(root_id, tree)
        new: set[str] = set()
        if roots:
            self._forget_offsets()  # and what it held of nodes deleted since
        for root_id in roots:
            new.update(self._build(root_id))
        self._forget_parts(old - new)
        return roots

    def _forget_offsets(self) -> None:
        self._offsets.clear()
        self._carried.clear()

    def _forget_parts(self, keys: Iterable[str]) -> None:
        """Parts without a body any more: their contacts end, their ray shapes go, and
        nothing is carried by them."""
        keys = list(keys)
        if keys:
            self._forget_offsets()
        for key in keys:
            self._poses.pop(key, None)
            self.tracker.removed(key)
            self._rays.remove(key)
            del self._ray_geometry[key]

    def _forget_tree(self, root_id: str, tree: Articulation) -> None:
        self.physics.remove_tree(root_id)
        for _, joint in tree.joints():
            self._motor_root.pop(joint.motor, None)
        self._joint_motors.pop(root_id, None)

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
            self.physics.add_tree(tree, base_pose(node), angles)
        except Exception:  # a bug: this tree is left out, the scene goes on
            self.failures += 1
            log.exception("the parts of %s in scene %s could not be placed", root_id, self._name)
            return []
        self._motor_root.update(dict.fromkeys(angles, root_id))
        self._joint_motors[root_id] = [self._nodes[motor] for motor in angles]
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
        self._place_nodes(root_id, keys, poses)
        return keys

    def _place_nodes(self, root_id: str, keys: Sequence[str], poses: list[Pose]) -> None:
        """Keep the poses Bullet found for the parts (sensors on them start from there)."""
        self._poses.update(zip(keys, poses))
        self._scales.update(zip(keys, self.physics.tree(root_id).scales()))

    def world_poses(self, nodes: list[Node]) -> tuple[np.ndarray, np.ndarray]:
        """World positions (n×3) and quaternions (n×4) of nodes: the pose in Bullet of the
        unscaled part that carries a node, composed with the node's offset from it (a
        sensor on a fingertip), for all such nodes at once; else the tree's own
        (:meth:`Node.world_pose`)."""
        self._read_poses()
        key = tuple(node.id for node in nodes)
        carried = self._carried.get(key)
        if carried is None:
            if len(self._carried) >= _CARRIED_SETS:
                self._carried.clear()
            carried = self._carried[key] = self._carriers(nodes)
        positions, quats = np.empty((len(nodes), 3)), np.empty((len(nodes), 4))
        for index in carried.own:
            positions[index], quats[index] = nodes[index].world_pose()
        if carried.hosts:
            hosts = [self._poses[host] for host in carried.hosts]
            positions[carried.rows], quats[carried.rows] = math3d.compose_arrays(
                np.array([p for p, _ in hosts]), np.array([q for _, q in hosts]),
                carried.positions, carried.quats)
        return positions, quats

    def _carriers(self, nodes: list[Node]) -> _Carried:
        """Which of ``nodes`` their parts carry, and their offsets, as arrays."""
        found = [self._offset(node) for node in nodes]
        rows = [index for index, host in enumerate(found) if host is not None]
        offsets = [found[index][1] for index in rows]  # type: ignore[index]
        return _Carried(own=[index for index, host in enumerate(found) if host is None],
                        rows=np.array(rows, dtype=np.int64),
                        hosts=[found[index][0] for index in rows],  # type: ignore[index]
                        positions=np.array([p for p, _ in offsets]).reshape(-1, 3),
                        quats=np.array([q for _, q in offsets]).reshape(-1, 4))

    def _offset(self, node: Node) -> tuple[str, Pose] | None:
        """The unscaled part that carries ``node`` and the node's pose relative to it; None
        when the tree's own pose must be used. Kept until a tree is built again (every
        change of a pose below a root, or of a parent, rebuilds its tree)."""
        if node.id in self._offsets:
            return self._offsets[node.id]
        chain: list[Node] = []
        host: Node | None = node
        while host is not None and host.id not in self._poses:
            if host.scale != UNIT_SCALE or host.is_motor:
                break
            chain.append(host)
            host = host.parent
        found: tuple[str, Pose] | None = None
        if host is not None and host.id in self._poses and self._scales[host.id] == UNIT_SCALE:
            offset: Pose = (math3d.ORIGIN, math3d.IDENTITY)
            for link in reversed(chain):
                offset = math3d.compose(offset, link.local_pose())
            found = (host.id, offset)
        self._offsets[node.id] = found
        return found

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
                    self._based.add(motor_id)  # a lone motor: its turn is its base's pose
        self._turned.clear()
        motors = self._joint_motors
        return {root_id for root_id in roots - rebuilt if self._guarded(root_id, lambda: self.physics.turn(
            root_id, [motor.angle for motor in motors[root_id]]))}  # type: ignore[attr-defined]

    def _place_bases(self, rebuilt: set[str]) -> set[str]:
        """Place the bases of the moved roots; the roots placed."""
        placed = set()
        for root_id in self._based:
            node = self._nodes.get(root_id)
            if root_id not in rebuilt and node is not None and self.physics.tree(root_id) and \
                    self._guarded(root_id, lambda: self.physics.move_base(root_id, base_pose(node))):
                placed.add(root_id)
        self._based.clear()
        return placed

    # --- contacts and sensors --------------------------------------------------------------

    def overlaps(self) -> Overlaps:
        """The pairs touching now, as far as one update's budget of tests measures."""
        self.sync()
        self.tracker.update()
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
        hosts = [sensor.host() for sensor in sensors]  # type: ignore[attr-defined]
        if exact:
            contacts = [self.touching(host) for host in hosts]
        else:
            of = self.tracker.overlaps().of
            contacts = [() if host is None else of(host.id) for host in hosts]
        return read_sensors(self._rays, sensors, contacts, *self.world_poses(sensors))
