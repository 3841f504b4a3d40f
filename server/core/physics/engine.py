"""The collision world: a narrow interface over one PyBullet ``DIRECT`` client.

Every tree of parts is one multibody (:mod:`.articulation`): a tick places its base and
sets all its joints in one call each, and reads its parts' poses from Bullet's forward
kinematics in one call. Kinematic mode, as in 1.0: nothing is ever stepped, so nothing
falls or gets pushed. Rays are not Bullet's: see :mod:`server.core.physics.raycast`.
Where each part is in Bullet, and contacts, poses and boxes by part:
:class:`~.bullet_parts.BulletParts` (``PhysicsWorld.parts``).
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import chain
from typing import Any, Iterator, Mapping, Sequence

import numpy as np

from ..kit.math3d import Pose, Vec3, rotate
from .articulation import NO_POSE, Articulation, check_links, multibody_arguments
from .bullet import pybullet, shape_arguments
from .bullet_parts import BulletParts
from .clearance import Clearance
from .dynamics import Dynamics
from .filter_groups import GROUND_GROUP, GROUND_MASK
from .self_contacts import dynamic_body
from .settings import Physics

ENGINE = "pybullet"  # the one physics engine (the viewer's engine= option must name it)
# Parts of one tree meet each other too, neighbours included (spec: self-collision); in
# dynamic mode, see self_contacts.py.
_SELF_COLLISION = pybullet.URDF_USE_SELF_COLLISION | pybullet.URDF_USE_SELF_COLLISION_INCLUDE_PARENT
# Manifold points that drift this far from where they were found are dropped (a part
# placed elsewhere keeps no stale point beyond it); Bullet's default is 0.02.
BREAKING_THRESHOLD = 0.0005
# PyBullet keeps about 1 kB for every body ever removed and never frees a shape; a fresh
# client after this many removals gives the memory back.
REBUILD_AFTER_REMOVALS = 10_000


@dataclass
class _Built:
    """A tree as built in PyBullet, with what a rebuild needs to make it again."""

    tree: Articulation
    body: int
    base_pose: Pose
    angles: list[float]          # of its joints, in the order of joints
    joints: dict[str, int]       # motor id -> link index of its joint
    joint_links: list[int]       # the same link indices, in that order
    part_links: list[int]        # link indices that carry parts, in tree.parts() order
    mount: int | None = None     # dynamic mode: a robot's mount (a constraint)
    # dynamic mode: centres of mass in their parts' frames (Bullet poses bodies by them)
    base_centre: Vec3 = (0.0, 0.0, 0.0)
    part_centres: list[Vec3] | None = None  # of the parts on links, in part_links order
    bullet_pose: Any = None  # dynamic mode: the base's pose as Bullet gave it when last read


class PhysicsWorld:
    """Trees of parts, one multibody each (:mod:`.articulation`), plus the ground plane y = 0.

    Parts are addressed by their node ids whatever link of whatever tree carries them
    (:attr:`parts`); a lone part is a tree with only a base. Shapes of equal geometry share
    one collision shape.
    """

    def __init__(self, physics: Physics = Physics()) -> None:
        self.physics = physics
        self.dynamics: Dynamics | None = None  # in dynamic mode
        self.parts = BulletParts()  # where each part is; contacts, poses and boxes by part
        self._client: int | None = None
        self._trees: dict[str, _Built] = {}
        self.removals = 0
        self.rebuilds = 0
        self._connect()

    def _connect(self) -> None:
        if self._client is None:
            self._client = pybullet.connect(pybullet.DIRECT)
        else:  # an empty world, as a new client's, in a millisecond (connect: 3-20 ms)
            pybullet.resetSimulation(physicsClientId=self._client)
        self._shapes: dict[tuple, int] = {}
        plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, planeNormal=[0, 1, 0],
                                              physicsClientId=self._client)
        self._ground = pybullet.createMultiBody(0, plane, physicsClientId=self._client)
        pybullet.setCollisionFilterGroupMask(self._ground, -1, GROUND_GROUP, GROUND_MASK,
                                             physicsClientId=self._client)
        pybullet.setPhysicsEngineParameter(contactBreakingThreshold=BREAKING_THRESHOLD,
                                           physicsClientId=self._client)
        self.dynamics = Dynamics(pybullet, self._client, self.physics) \
            if self.physics.dynamic else None
        self._clearance = Clearance(pybullet, self._client, self._robot_bodies,
                                    lambda: self.dynamics.steps, self._ground) \
            if self.dynamics else None  # type: ignore[union-attr]
        self.parts.connect(self._client, self._ground, self.dynamics)

    def close(self) -> None:
        """Release the PyBullet client."""
        if self._client is not None:
            pybullet.disconnect(physicsClientId=self._client)
            self._client = None

    @property
    def client(self) -> int:
        """The PyBullet client of this world (for what no method here offers)."""
        return self._client  # type: ignore[return-value]

    def __contains__(self, key: str) -> bool:
        return key in self.parts

    def __len__(self) -> int:
        return len(self.parts)

    # --- trees ---------------------------------------------------------------------------

    def tree(self, root: str) -> Articulation | None:
        """The tree built for ``root`` (None: none is)."""
        built = self._trees.get(root)
        return None if built is None else built.tree

    def links_held(self, root: str) -> int:
        """How many links the engine's multibody of ``root``'s tree has (its tree's, unless
        the engine cut it short)."""
        return pybullet.getNumJoints(self._trees[root].body, physicsClientId=self._client)

    def add_tree(self, tree: Articulation, base_pose: Pose, angles: Mapping[str, float],
                 mount: Pose | None = None) -> None:
        """Build ``tree`` as one multibody, its base at ``base_pose``, its joints at ``angles``
        and (dynamic mode, a robot) its mount at ``mount`` (None: at its base) (a tree past
        the engine's links is refused: PyBullet would cut it short)."""
        check_links(tree.root, len(tree.links))
        client, dynamics = self._client, self.dynamics
        free = self._clearance is not None and not tree.mounted and not tree.static
        arguments = multibody_arguments(tree, base_pose, self._shape, pybullet.JOINT_REVOLUTE,
                                        pybullet.JOINT_FIXED, pybullet.JOINT_PRISMATIC)
        if dynamics is not None:
            arguments["baseMass"], arguments["linkMasses"] = dynamics.masses(tree)
            base_centre, centres = dynamics.centres(tree)
            arguments["baseInertialFramePosition"] = base_centre
            arguments["linkInertialFramePositions"] = [
                tuple(a + b for a, b in zip(link.shape[0], rotate(link.shape[1], centre)))
                for link, centre in zip(tree.links, centres)]
        body = self._create(tree, arguments, angles)
        joints = {joint.motor: k for k, joint in tree.joints()}
        links = [k for k, link in enumerate(tree.links) if link.part is not None]
        built = _Built(tree, body, base_pose, [], joints, list(joints.values()), links)
        self._trees[tree.root] = built
        places = ([(tree.base_part, -1, tree.base_geometry)] if tree.base_part is not None else []) \
            + [(tree.links[k].part, k, tree.links[k].geometry) for k in links]
        self.parts.add(body, len(tree.links), places)  # type: ignore[arg-type]
        if dynamics is not None:
            built.mount = dynamics.made(body, tree, base_pose, built.joint_links, mount)
            built.base_centre = base_centre
            built.part_centres = [centres[k] for k in links]
        self.turn(tree.root, [angles[motor] for motor in joints])
        if free:  # where it is, or the nearest clear spot (read after the next step)
            self._clearance.place(body, *pybullet.getBasePositionAndOrientation(  # type: ignore[union-attr]
                body, physicsClientId=client))

    def _create(self, tree: Articulation, arguments: dict[str, Any],
                angles: Mapping[str, float]) -> int:
        """The tree's multibody (dynamic mode: :func:`.self_contacts.dynamic_body`)."""
        if self.dynamics is None:
            return pybullet.createMultiBody(physicsClientId=self._client, flags=_SELF_COLLISION,
                                            **arguments)
        body, removed = dynamic_body(pybullet, self._client, tree, arguments, angles)
        self.removals += removed
        return body

    @property
    def cleared(self) -> int:
        """Dynamic mode: free bodies moved out of others so far (:mod:`.clearance`)."""
        return 0 if self._clearance is None else self._clearance.moved

    def _robot_bodies(self) -> set[int]:
        """The bodies of robots (dynamic mode: those with a mount)."""
        return {built.body for built in self._trees.values() if built.mount is not None}

    def remove_tree(self, root: str) -> None:
        """Take the tree of ``root`` out of the world."""
        built = self._trees.pop(root)
        if self.dynamics is not None:
            self.dynamics.removed(built.body, built.mount)
            self._clearance.removed(built.body)  # type: ignore[union-attr]
        self.parts.remove(built.body, built.tree.parts())
        pybullet.removeBody(built.body, physicsClientId=self._client)
        self.removals += 1

    def move_base(self, root: str, pose: Pose) -> None:
        """Place the base of the tree of ``root`` at a world pose (dynamic mode: a robot's
        mount moves there and its base follows; anything else is put there at rest)."""
        built = self._trees[root]
        if self.dynamics is None:
            pybullet.resetBasePositionAndOrientation(built.body, pose[0], pose[1],
                                                     physicsClientId=self._client)
        elif built.mount is not None:
            self.dynamics.mount(built.mount, pose)
        else:  # a script's setPosition puts even a static part elsewhere
            self.dynamics.teleport(built.body, _shifted(pose, built.base_centre))
            if not built.tree.static:
                self._clearance.place(built.body, *_shifted(pose, built.base_centre))  # type: ignore[union-attr]
        built.base_pose = pose

    def place_mount(self, root: str, pose: Pose) -> None:
        """Dynamic mode: a robot's mount put at ``pose`` at once, its base left where it is
        (a restored robot's: it holds from its first step as it did when it was saved)."""
        built = self._trees[root]
        if self.dynamics is not None and built.mount is not None:
            self.dynamics.place_mount(built.mount, pose)

    def turn(self, root: str, angles: list[float]) -> None:
        """Set every joint of the tree of ``root`` in one call, to ``angles`` in the order
        of its joints (:meth:`Articulation.joints`): all of them, as one list is cheaper
        than picking the turned ones out."""
        built = self._trees[root]
        if built.joints:
            pybullet.resetJointStatesMultiDof(built.body, built.joint_links,
                                              [[angle] for angle in angles],
                                              physicsClientId=self._client)
            built.angles = angles

    def part_poses(self, root: str) -> tuple[Sequence[str], list[Pose]]:
        """The world pose of every part of the tree of ``root`` (Bullet's forward kinematics,
        one call for all links)."""
        built = self._trees[root]
        keys, poses = built.tree.parts(), []
        if built.tree.base_part is not None:
            poses.append(built.base_pose)
        if built.part_links:
            states = self._link_states(built)
            if built.part_centres is None:
                poses += [(state[0], state[1]) for state in states]
            else:  # Bullet gave where their centres of mass are
                poses += [_shifted((state[0], state[1]), centre, -1)
                          for state, centre in zip(states, built.part_centres)]
        return keys, poses

    def part_pose_rows(self, root: str) -> tuple[tuple[str, ...], np.ndarray]:
        """:meth:`part_poses` as one row of seven numbers (position, quaternion) a part:
        the same numbers, taken from Bullet's states straight into the array (a tick's
        sensing reads every moved tree: the tuples and the dict of poses between were a
        tenth of it)."""
        built = self._trees[root]
        keys = built.tree.parts()
        if built.part_centres is not None:  # dynamic mode: shifted from the centres, one by one
            poses = self.part_poses(root)[1]
            return keys, np.array([p + q for p, q in poses], float).reshape(len(keys), 7)
        states = self._link_states(built) if built.part_links else ()
        numbers = chain.from_iterable(state[0] + state[1] for state in states)
        if built.tree.base_part is not None:
            numbers = chain(built.base_pose[0] + built.base_pose[1], numbers)
        return keys, np.fromiter(numbers, float, 7 * len(keys)).reshape(len(keys), 7)

    def _link_states(self, built: _Built) -> list[tuple]:
        # Bullet's own link frames as its last change left them: placing a base, setting
        # joints and stepping each end in its forward kinematics, so running them again
        # here (computeForwardKinematics) was 2 % of a tick's sensing, for nothing
        return pybullet.getLinkStates(built.body, built.part_links, physicsClientId=self._client)

    def _shape(self, geometry: dict[str, Any], frame: Pose = NO_POSE) -> int:
        arguments = shape_arguments(geometry)
        if frame != NO_POSE:
            arguments.update(collisionFramePosition=frame[0], collisionFrameOrientation=frame[1])
        key = tuple((name, tuple(map(tuple, v)) if name == "vertices" else
                     tuple(v) if isinstance(v, (list, tuple)) else v)
                    for name, v in arguments.items())
        shape = self._shapes.get(key)
        if shape is None:
            shape = self._shapes[key] = pybullet.createCollisionShape(
                physicsClientId=self._client, **arguments)
        return shape

    # --- lone parts ----------------------------------------------------------------------

    def add(self, key: str, geometry: dict[str, Any], pose: Pose) -> None:
        """A lone part: a tree of only a base shaped by a part geometry."""
        self.add_tree(Articulation(key, key, geometry), pose, {})

    def remove(self, key: str) -> None:
        """Take the lone part ``key`` out of the world."""
        self.remove_tree(key)

    def move(self, key: str, pose: Pose) -> None:
        """Place the lone part ``key`` at a world pose."""
        self.move_base(key, pose)

    # --- dynamic mode --------------------------------------------------------------------

    def drive(self, root: str, targets: list[float], torques: list[float],
              speeds: list[float]) -> None:
        """Dynamic mode: the joints of the tree of ``root`` toward ``targets`` (in the order
        of its joints), each with at most its torque (a sliding joint's: its force) and no
        faster than its speed (inf: no limit)."""
        built = self._trees[root]
        if built.joints and self.dynamics is not None:
            self.dynamics.drive(built.body, built.joint_links, targets, torques, speeds,
                                built.tree.sliding)

    def motion(self, root: str, bullet_pose: Any = None) -> tuple[Pose | None, list[float]]:
        """Dynamic mode: where the base of the tree of ``root`` is (None: static) and its
        joints' real angles, in the order of its joints (``bullet_pose``: its base's pose
        as Bullet just gave it, if read)."""
        built, dynamics = self._trees[root], self.dynamics
        assert dynamics is not None
        if bullet_pose is not None:
            bullet_pose = (tuple(bullet_pose[0]), tuple(bullet_pose[1]))
        pose = None if built.tree.static else \
            _shifted(bullet_pose or dynamics.base_pose(built.body), built.base_centre, -1)
        angles = dynamics.joint_angles(built.body, built.joint_links) if built.joints else []
        if pose is not None:
            built.base_pose = pose
        built.angles = angles
        return pose, angles

    def joint_motion(self, root: str) -> tuple[list[float], list[float]]:
        """Dynamic mode: each joint's speed (rad/s; a sliding joint's, scene units/s) and
        the torque (N·m; a sliding joint's force, N) it was driven with in the last step,
        of the tree of ``root``, in the order of its joints (zeros before its first step)."""
        built, dynamics = self._trees[root], self.dynamics
        if dynamics is None or not built.joints:
            return [0.0] * len(built.joints), [0.0] * len(built.joints)
        return dynamics.joint_motion(built.body, built.joint_links, built.tree.sliding)

    def motions(self) -> Iterator[tuple[str, Pose | None, list[float]]]:
        """Dynamic mode: :meth:`motion` of each tree Bullet may have moved since the last
        call: every tree with joints, and the free bodies whose base is not bit for bit
        where it was. A sleeping body is not integrated, so a settled heap of 2 000 balls
        costs a call and a comparison each, not a pose's conversion and comparison."""
        read, client = pybullet.getBasePositionAndOrientation, self._client
        for root, built in self._trees.items():
            if not built.joints:
                if built.tree.static:
                    continue
                now = read(built.body, physicsClientId=client)
                if now == built.bullet_pose:
                    continue
                built.bullet_pose = now
                yield (root, *self.motion(root, now))
            else:
                yield (root, *self.motion(root))

    def roots(self) -> list[str]:
        """The roots of every tree built."""
        return list(self._trees)

    # --- memory --------------------------------------------------------------------------

    def needs_rebuild(self) -> bool:
        """True when enough bodies were removed that a fresh client would free memory."""
        return self.removals >= REBUILD_AFTER_REMOVALS or \
            len(self._shapes) > 2 * len(self.parts) + REBUILD_AFTER_REMOVALS // 10

    def rebuild(self, physics: Physics | None = None) -> None:
        """Move every tree into a fresh PyBullet world (with other ``physics``, when
        given): the client's is emptied, which frees what it held; trees start at rest where
        they are."""
        trees = list(self._trees.values())
        self.physics = physics or self.physics
        self._trees = {}  # every part crowded again
        self._connect()
        for built in trees:
            self.add_tree(built.tree, built.base_pose, dict(zip(built.joints, built.angles)))
        self.removals = 0
        self.rebuilds += 1


def _shifted(pose: Pose, centre: Vec3, sign: int = 1) -> Pose:
    """A part's pose as the pose of its centre of mass (or back, ``sign`` −1)."""
    if centre == (0.0, 0.0, 0.0):
        return pose
    offset = rotate(pose[1], centre)
    return tuple(p + sign * o for p, o in zip(pose[0], offset)), pose[1]  # type: ignore[return-value]
