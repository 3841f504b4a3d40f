"""Dynamic mode of a scene's bodies: motors driven toward their targets, the world stepped
through a tick's time, and what the steps moved; motors' speeds and torques as the last
step left them.

A world that neither changed nor moved in its last steps stays at rest (Dynamics.advance
takes no step of it). A follower motor aims at its share of where its leader really is.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Mapping, NamedTuple, Sequence

from ..model.node import Node
from ..physics.engine import PhysicsWorld

if TYPE_CHECKING:
    from ..kit.math3d import Pose

HAIR = 1e-9  # a joint or body that moved less than this (m, rad) has not moved


def _apart(a: Pose, b: Pose) -> bool:
    return any(abs(x - y) > HAIR for x, y in zip((*a[0], *a[1]), (*b[0], *b[1])))


class Steps(NamedTuple):
    """What :meth:`Stepping.advance` did."""

    seconds: float  # the world went through (less than asked when it is behind)
    angles: dict[str, float]  # motors' new angles
    poses: dict[str, Pose]  # free roots' new poses
    moved: list[str]  # the roots whose parts moved
    stirred: bool  # motors driven anew, or anything moved: contacts are read again


class Stepping:
    """Steps of one scene's physics world, given its nodes and, per root, the motors of its
    tree's joints in order (kept by :class:`~.bodies.SceneBodies` as it builds trees)."""

    def __init__(self, physics: PhysicsWorld, nodes: Mapping[str, Node],
                 joint_motors: Mapping[str, list[Node]]) -> None:
        self._physics = physics
        self._nodes = nodes
        self._joint_motors = joint_motors
        self._followers: dict[str, list[Node]] = {}  # root -> its motors that follow another
        self.targets_due = False  # motors' targets to be driven toward
        # anything built, put or driven since steps were last taken (its own flag: a tick
        # that took no step, its time too short or a paused scene's stand, read the
        # contacts and so cleared the scene's, and a still world then counted every later
        # step as rest: a ball put up high in it hung there)
        self.changed = True
        self.still = False  # the last steps moved nothing

    def built(self, root_id: str, motors: list[Node]) -> None:
        """The tree of ``root_id`` built, with these motors as its joints: driven from the
        next step."""
        followers = [m for m in motors if m.following is not None]  # type: ignore[attr-defined]
        if followers:
            self._followers[root_id] = followers
        else:
            self._followers.pop(root_id, None)
        if self._physics.dynamics is not None:
            self.targets_due = True

    def forgot(self, root_id: str) -> None:
        """The tree of ``root_id`` taken out."""
        self._followers.pop(root_id, None)

    def advance(self, dt: float, exact: bool) -> Steps:
        """Drive the motors, step the world through ``dt`` (what moved more than a hair
        has moved). ``exact``: every step, whatever it costs (a script steps the scene:
        Dynamics.advance)."""
        if self._followers:
            self._follow()
        driven = self.targets_due
        if driven:
            self._drive()
        dynamics = self._physics.dynamics
        assert dynamics is not None
        at_rest = self.still and not self.changed
        steps = dynamics.advance(dt, still=at_rest, exact=exact)
        if not steps or at_rest:
            return Steps(steps * dynamics.physics.step, {}, {}, [], driven)
        self.changed = False
        angles: dict[str, float] = {}
        poses: dict[str, Pose] = {}
        moved_roots = []
        for root_id, pose, joints in self._physics.motions():
            moved = False
            for motor, angle in zip(self._joint_motors.get(root_id, ()), joints):
                if abs(motor.angle - angle) > HAIR:  # type: ignore[attr-defined]
                    angles[motor.id] = angle
                    moved = True
            if pose is not None and _apart(self._nodes[root_id].local_pose(), pose):
                poses[root_id] = pose
                moved = True
            if moved:
                moved_roots.append(root_id)
        self.still = not (angles or poses or dynamics.woke)
        return Steps(steps * dynamics.physics.step, angles, poses, moved_roots,
                     driven or not self.still)

    def _follow(self) -> None:
        """Each follower aims at its share of where its leader really is (a finger whose
        first joint an object stops stops curling, as a linkage does; Bullet's own gear
        constraint was tried and measured wrong on a robot's floating base)."""
        for followers in self._followers.values():
            for follower in followers:
                leader = follower.leader()  # type: ignore[attr-defined]
                if leader is None:
                    continue
                aim = follower.share_of(leader.angle)  # type: ignore[attr-defined]
                if aim is not None and aim != follower.target:  # type: ignore[attr-defined]
                    follower.target = aim  # type: ignore[attr-defined]
                    self.targets_due = True

    def _drive(self) -> None:
        """Every tree's joints toward their motors' targets, with their torques and speeds."""
        for root_id, motors in self._joint_motors.items():
            self._physics.drive(root_id, [m.target for m in motors],  # type: ignore[attr-defined]
                                [m.get_max_torque() for m in motors],  # type: ignore[attr-defined]
                                [m.get_max_speed() for m in motors])  # type: ignore[attr-defined]
        self.targets_due = False
        self.changed = True

    def motor_motion(self, motors: Sequence[Node]) -> list[tuple[float, float]]:
        """Each motor's speed (rad/s; a slider's, scene units/s) and the torque (a slider's
        force) it drove with in the last step, N·m (N), positive turning its angle up; 0, 0
        in kinematic mode, where motors jump to their angles, and for a motor not yet
        built into its tree."""
        out = []
        read: dict[str, tuple[list[float], list[float]]] = {}
        for motor in motors:
            root_id = motor.root().id
            built = self._joint_motors.get(root_id, [])
            if self._physics.dynamics is None or motor not in built:
                out.append((0.0, 0.0))
                continue
            if root_id not in read:  # one read of Bullet per tree
                read[root_id] = self._physics.joint_motion(root_id)
            speeds, efforts = read[root_id]
            index = built.index(motor)
            out.append((speeds[index], efforts[index]))
        return out
