"""A tree of parts compiled for the engine: one PyBullet multibody per tree.

The one structure that kinematic ticks, a dynamic mode and a URDF export all read:
*links* carry the physical parts, *joints* are the motors (revolute, about one axis of
the joint frame, within limits), and every slot, sensor or bare node between them folds
into the fixed transforms (``origin``: a link's joint frame in its parent link's frame;
``shape``: where the part sits in its own link's frame). A link carries no part only where
two joints meet with no part between them.

PyBullet's conventions, measured (tests/server/core/physics/test_articulation.py): a
link's ``linkPositions``/``linkOrientations`` are its joint frame in the parent's *link*
frame; a link's collision shape sits in its link frame (so the part's offset goes into the
shape's frame); ``getLinkStates`` reports the link's *inertial* frame first, so the part's
offset is also the inertial frame and the part's world pose is read without composing.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any, Callable, Mapping

from ..kit.errors import LimitExceeded
from ..kit.math3d import IDENTITY, ORIGIN, Pose, Vec3, axis_angle, compose
from .geometry import scaled

NO_POSE: Pose = (ORIGIN, IDENTITY)
UNSCALED: Vec3 = (1.0, 1.0, 1.0)
# PyBullet's multibody holds at most this many links. It drops the rest without a word,
# and a scene addressing link 127 then ended its process (signal 11): a larger tree is
# refused, naming this (a fixed figure of the engine, no flag changes it).
MAX_LINKS = 127


def check_links(root: str, links: int) -> None:
    """Refuse a tree of ``root`` that would have ``links`` links, past :data:`MAX_LINKS`."""
    if links > MAX_LINKS:
        raise LimitExceeded(
            f"{root} would be a tree of {links} links (its parts that move or sit apart, and "
            f"a link between two motors with no part between them); the physics engine holds "
            f"at most {MAX_LINKS} in one tree: attach the rest to a robot of its own",
            limit="treeLinks", value=MAX_LINKS, object=root)


@dataclass(frozen=True)
class Joint:
    """A motor as a joint: its value turns the link about ``axis`` (radians) or, for a
    sliding motor, moves it along ``axis`` (scene units)."""

    motor: str   # the motor's node id
    axis: Vec3   # a unit axis of the joint frame, negated for a flipped motor
    lower: float
    upper: float
    slides: bool = False  # a prismatic joint (its limits are lengths)

    def motion(self, value: float) -> Pose:
        """The joint's child frame in its joint frame at ``value`` (in the tree's lengths)."""
        if self.slides:
            return tuple(a * value for a in self.axis), IDENTITY  # type: ignore[return-value]
        return ORIGIN, axis_angle(self.axis, value)

    def stretched(self, factor: float) -> Joint:
        """The joint of a tree ``factor`` times as long (a sliding joint's limits with it)."""
        if not self.slides:
            return self
        return replace(self, lower=self.lower * factor, upper=self.upper * factor)


@dataclass(frozen=True)
class Link:
    """One link: its place below its parent, its joint, and the part it carries."""

    parent: int             # the parent link's index; -1 is the base
    origin: Pose            # the joint frame in the parent link's frame
    joint: Joint | None     # None: fixed to its parent
    part: str | None        # the physical part's id; None between two joints
    shape: Pose = NO_POSE   # the part's frame in this link's frame
    geometry: dict[str, Any] | None = field(default=None, compare=False)
    scale: Vec3 = UNSCALED  # the part's world scale (its geometry is already stretched by it)
    mass: float | None = None      # kg, given by setMass (None: from volume and density)
    friction: float | None = None  # given by setFriction (None: the scene's)
    centre: Vec3 | None = None     # centre of mass in the part's frame, from a robot file
    inertia: Vec3 | None = None    # principal moments (kg·length²) about it, from a robot file

    def stretched(self, factor: float) -> Link:
        """The same link with every length ``factor`` times as long (its masses kept)."""
        return replace(self, origin=stretched_pose(self.origin, factor),
                       joint=None if self.joint is None else self.joint.stretched(factor),
                       shape=stretched_pose(self.shape, factor),
                       geometry=None if self.geometry is None else scaled(self.geometry, (factor,) * 3),
                       scale=tuple(s * factor for s in self.scale),
                       centre=None if self.centre is None else tuple(c * factor for c in self.centre),
                       inertia=None if self.inertia is None else tuple(i * factor ** 2 for i in self.inertia))


def stretched_pose(pose: Pose, factor: float) -> Pose:
    """A pose whose place is ``factor`` times as far from its frame's origin."""
    return tuple(p * factor for p in pose[0]), pose[1]  # type: ignore[return-value]


@dataclass(frozen=True)
class Articulation:
    """A tree compiled: its base (the tree's root, perhaps a part itself) and its links.

    The base's pose and the joints' angles are state, not structure: a tick sets them
    without building the multibody again.
    """

    root: str
    base_part: str | None = None
    base_geometry: dict[str, Any] | None = field(default=None, compare=False)
    links: tuple[Link, ...] = ()
    base_scale: Vec3 = UNSCALED
    base_mass: float | None = None      # as Link.mass, for the base's part
    base_friction: float | None = None  # as Link.friction
    mounted: bool = False  # a robot: in dynamic mode its base is held where it is put
    static: bool = False   # never moves in dynamic mode (a table)

    def in_metres(self, unit: float) -> Articulation:
        """The tree of a scene of ``unit`` metres per scene unit, with its lengths in metres
        (what files are written from)."""
        if unit == 1.0:
            return self
        geometry = self.base_geometry
        return replace(self, base_geometry=None if geometry is None else scaled(geometry, (unit,) * 3),
                       base_scale=tuple(s * unit for s in self.base_scale),
                       links=tuple(link.stretched(unit) for link in self.links))

    def scales(self) -> list[Vec3]:
        """The world scale of every physical part, in :meth:`parts` order."""
        mine = [self.base_scale] if self.base_part is not None else []
        return mine + [link.scale for link in self.links if link.part is not None]

    def parts(self) -> tuple[str, ...]:
        """Every physical part's id, the base's first."""
        return self._part_ids

    @cached_property
    def _part_ids(self) -> tuple[str, ...]:  # a tick asks for them for every moved tree
        mine = [self.base_part] if self.base_part is not None else []
        return tuple(mine + [link.part for link in self.links if link.part is not None])

    def joints(self) -> list[tuple[int, Joint]]:
        """(link index, joint) of every joint, in link order."""
        return [(k, link.joint) for k, link in enumerate(self.links) if link.joint is not None]

    def link_poses(self, values: Mapping[str, float]) -> list[Pose]:
        """Every link's frame in the base's frame with each joint at its motor's value in
        ``values`` (a motor left out: at 0), as Bullet's forward kinematics places them."""
        poses: list[Pose] = []
        for link in self.links:
            frame = compose(NO_POSE if link.parent < 0 else poses[link.parent], link.origin)
            if link.joint is not None:
                frame = compose(frame, link.joint.motion(values.get(link.joint.motor, 0.0)))
            poses.append(frame)
        return poses

    @cached_property
    def sliding(self) -> tuple[bool, ...]:
        """Which joints slide, in the order of :meth:`joints` (a tick drives them all)."""
        return tuple(joint.slides for _, joint in self.joints())


# --- PyBullet ----------------------------------------------------------------------------

LINK_MASS = 1.0          # a part's link (kinematic: only needed so Bullet tests it)
BETWEEN_MASS = 1e-3      # a link where two joints meet, carrying nothing


def multibody_arguments(tree: Articulation, base_pose: Pose,
                        shape_of: Callable[[dict[str, Any], Pose], int],
                        revolute: int, fixed: int, prismatic: int) -> dict[str, Any]:
    """``createMultiBody`` arguments for ``tree`` at ``base_pose``.

    ``shape_of(geometry, frame)`` gives a collision shape placed at ``frame`` in its link;
    ``revolute``, ``fixed`` and ``prismatic`` are PyBullet's joint type constants.
    """
    links = tree.links
    base_shape = -1 if tree.base_geometry is None else shape_of(tree.base_geometry, NO_POSE)
    return {  # a base without a part is static; with one it must not be (Bullet skips static pairs)
        "baseMass": 0.0 if base_shape < 0 else LINK_MASS, "baseCollisionShapeIndex": base_shape,
        "basePosition": base_pose[0], "baseOrientation": base_pose[1],
        "linkMasses": [LINK_MASS if link.part is not None else BETWEEN_MASS for link in links],
        "linkCollisionShapeIndices": [-1 if link.geometry is None else
                                      shape_of(link.geometry, link.shape) for link in links],
        "linkVisualShapeIndices": [-1] * len(links),
        "linkPositions": [link.origin[0] for link in links],
        "linkOrientations": [link.origin[1] for link in links],
        "linkInertialFramePositions": [link.shape[0] for link in links],
        "linkInertialFrameOrientations": [link.shape[1] for link in links],
        "linkParentIndices": [link.parent + 1 for link in links],  # PyBullet: 0 is the base
        "linkJointTypes": [fixed if link.joint is None else prismatic if link.joint.slides
                           else revolute for link in links],
        "linkJointAxis": [(0.0, 0.0, 1.0) if link.joint is None else link.joint.axis
                          for link in links],
    }
