"""A robot read from a file (URDF or MJCF), in the one form scenes build robots from.

The readers (:mod:`.urdf_reading`, :mod:`.mjcf_reading`) turn a description and its meshes
into a :class:`RobotDescription`: its links in tree order (every parent before its
children), each with the joint that holds it to its parent, its drawn mesh (a GLB of its
visual elements, kept as an upload), its collision envelope (the convex hull of its
collision elements, as a mesh part's) and its inertia; and the joints that follow others.
It is kept as JSON beside the meshes (``<hash>.robot``), so a scene document names a robot
by that file, as it names a mesh; every figure is checked again when a scene reads it,
since a file in the uploads folder may have been put there by hand.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from ..kit.errors import BadAsset
from ..kit.limits import MAX_COORDINATE, MAX_SIZE
from ..kit.math3d import IDENTITY, ORIGIN, Pose, Vec3
from .articulation import MAX_LINKS

FORMAT = "virtual-prosthetics-robot"
VERSION = 1
JOINT_KINDS = ("revolute", "prismatic", "fixed")
MAX_NAME = 200


@dataclass(frozen=True)
class JointDescription:
    """How a link hangs on its parent: a motor that turns (``revolute``) or slides
    (``prismatic``), or rigidly (``fixed``)."""

    name: str
    kind: str
    origin: Pose = (ORIGIN, IDENTITY)  # the joint frame in the parent link's frame
    axis: Vec3 = (0.0, 0.0, 1.0)       # a unit vector of the joint frame
    lower: float = -math.inf           # radians (prismatic: metres)
    upper: float = math.inf
    effort: float | None = None        # N·m (prismatic: N) the file allows (None: not given)


@dataclass(frozen=True)
class LinkDescription:
    """One link: its place in the tree, what it looks like, what it collides as, its mass."""

    name: str
    parent: int                        # the parent's index in ``links``; -1: the root
    joint: JointDescription | None     # None for the root
    mesh: str | None = None            # the uploaded GLB of its visual elements (link frame)
    hull: tuple[Vec3, ...] | None = None  # collision envelope points (link frame)
    mass: float | None = None          # kg
    centre: Vec3 | None = None         # centre of mass (link frame)
    inertia: Vec3 | None = None        # principal moments about the centre (kg·m²)
    friction: float | None = None


@dataclass(frozen=True)
class Coupling:
    """A joint that turns with another: ``follower = ratio · leader + offset``."""

    follower: str
    leader: str
    ratio: float = 1.0
    offset: float = 0.0


@dataclass(frozen=True)
class RobotDescription:
    """A robot as a file describes it (see the module's docstring)."""

    name: str
    source: str                                  # "urdf" or "mjcf"
    links: tuple[LinkDescription, ...]
    couplings: tuple[Coupling, ...] = field(default=())

    def motors(self) -> list[JointDescription]:
        """The joints that become motors, in link order (the robot's motor order)."""
        return [link.joint for link in self.links
                if link.joint is not None and link.joint.kind != "fixed"]

    def to_json(self) -> bytes:
        """The description as the JSON file it is kept in (infinite limits as strings)."""
        body = {"format": FORMAT, "version": VERSION, **asdict(self)}
        return json.dumps(_wire(body), sort_keys=True, separators=(",", ":")).encode()

    @staticmethod
    def from_json(data: bytes) -> RobotDescription:
        """A kept description, every figure checked (:class:`BadAsset` naming what is wrong)."""
        try:
            body = json.loads(data)
            if body.pop("format") != FORMAT or body.pop("version") != VERSION:
                raise ValueError("not a robot description of this version")
            links = tuple(_link(k, entry) for k, entry in enumerate(body["links"]))
            couplings = tuple(Coupling(str(c["follower"]), str(c["leader"]), _finite(c["ratio"]),
                                       _finite(c["offset"])) for c in body["couplings"])
            return checked(RobotDescription(str(body["name"]), str(body["source"]), links, couplings))
        except BadAsset:
            raise
        except (ValueError, KeyError, TypeError, AttributeError) as error:
            raise BadAsset(f"the robot file does not read as a robot description: "
                           f"{str(error)[:200]}") from None


def checked(robot: RobotDescription) -> RobotDescription:
    """``robot``, or :class:`BadAsset` naming the first figure a scene cannot build."""
    if not robot.links:
        raise BadAsset(f"robot {robot.name!r} has no links")
    if len(robot.links) > MAX_LINKS:
        raise BadAsset(f"robot {robot.name!r} has {len(robot.links)} links; a robot holds at "
                       f"most {MAX_LINKS} (the physics engine's bound for one tree)")
    names = {joint.name for joint in robot.motors()}
    for k, link in enumerate(robot.links):
        if not -1 <= link.parent < k or (link.parent == -1) != (k == 0):
            raise BadAsset(f"link {link.name!r}: its parent must come before it, and only the "
                           f"first link is the root")
        for point in link.hull or ():
            _within(point, MAX_SIZE, f"link {link.name!r} envelope")
        if link.joint is not None:
            _within(link.joint.origin[0], MAX_COORDINATE, f"joint {link.joint.name!r} origin")
    for coupling in robot.couplings:
        for name in (coupling.follower, coupling.leader):
            if name not in names:
                raise BadAsset(f"coupling of {coupling.follower!r} to {coupling.leader!r}: the "
                               f"robot has no turning joint {name!r}")
    return robot


def diagonal_in(turn: np.ndarray, tensor: np.ndarray) -> Vec3:
    """The moments of an inertia tensor given in a frame turned by ``turn`` (3×3) from the
    link's, about the link's axes (the products are dropped: Bullet takes a diagonal)."""
    return tuple(max(float(d), 0.0) for d in np.diag(turn @ tensor @ turn.T))  # type: ignore[return-value]


def _link(index: int, entry: dict[str, Any]) -> LinkDescription:
    joint = entry["joint"]
    if joint is not None:
        if joint["kind"] not in JOINT_KINDS:
            raise ValueError(f"joint {joint['name']!r} is of kind {joint['kind']!r}")
        position, rotation = joint["origin"]
        joint = JointDescription(_name(joint["name"]), joint["kind"],
                                 (_vector(position, 3), _unit(rotation, 4)),
                                 _unit(joint["axis"], 3), _limit(joint["lower"]),
                                 _limit(joint["upper"]), _optional(joint["effort"]))
        if joint.lower > joint.upper:
            raise ValueError(f"joint {joint.name!r} has its lower limit above its upper one")
    hull = entry["hull"]
    centre, inertia = entry["centre"], entry["inertia"]
    return LinkDescription(
        _name(entry["name"]), int(entry["parent"]), joint,
        None if entry["mesh"] is None else str(entry["mesh"]),
        None if hull is None else tuple(_vector(p, 3) for p in hull),
        _optional(entry["mass"], positive=True), None if centre is None else _vector(centre, 3),
        None if inertia is None else _vector(inertia, 3), _optional(entry["friction"]))


def _name(value: Any) -> str:
    if not isinstance(value, str) or not 0 < len(value) <= MAX_NAME:
        raise ValueError(f"a name must be a string of 1 to {MAX_NAME} characters, got {value!r:.60}")
    return value


def _finite(value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"expected a finite number, got {value!r:.60}")
    return float(value)


def _limit(value: Any) -> float:
    if value in ("Infinity", "-Infinity"):
        return math.inf if value == "Infinity" else -math.inf
    return _finite(value)


def _optional(value: Any, positive: bool = False) -> float | None:
    if value is None:
        return None
    number = _finite(value)
    if number < 0 or (positive and number == 0):
        raise ValueError(f"expected a {'positive' if positive else 'non-negative'} number, got {number}")
    return number


def _vector(value: Any, size: int) -> Any:
    if not isinstance(value, list) or len(value) != size:
        raise ValueError(f"expected {size} numbers, got {value!r:.60}")
    return tuple(_finite(v) for v in value)


def _unit(value: Any, size: int) -> Any:
    vector = _vector(value, size)
    norm = math.sqrt(sum(v * v for v in vector))
    if not 1e-9 < norm < 1e9:
        raise ValueError(f"expected a direction, got {value!r:.60}")
    return vector if abs(norm - 1.0) < 1e-12 else tuple(v / norm for v in vector)


def _within(point: Vec3, bound: float, label: str) -> None:
    if max(abs(c) for c in point) > bound:
        raise BadAsset(f"{label}: coordinates lie within ±{bound:g} m, got {point}")


def _wire(value: Any) -> Any:
    """Tuples as lists and infinities as the strings JSON can hold."""
    if isinstance(value, dict):
        return {k: _wire(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_wire(v) for v in value]
    if isinstance(value, float) and math.isinf(value):
        return "Infinity" if value > 0 else "-Infinity"
    return value
