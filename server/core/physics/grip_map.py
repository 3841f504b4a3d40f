"""A hand's grip map, derived from its kinematics: its digits, the motors that close each
one and how far, which digit opposes the others, and which way the hand faces.

Written here because no library reads a grip off an arbitrary kinematic tree (grasp
planners such as GraspIt! take a hand-written ``eigengrasp`` file for each hand). The rules,
on the tree with its motors at rest (their defaults):

- **Digits** are the chains of joints from the palm to the tips: a tip is a part with no
  part below it and a joint above it; the palm is the deepest part all digits hang from.
- A digit **closes** with the run of motors at its end whose axes are parallel (a
  finger's flexion joints; a jaw's one joint). Each closes towards the limit (without
  limits: a turn of :data:`SPAN`) that brings its tip nearer the palm's centre, and
  opens to where its tip is furthest from it (the digit straight).
- **The opposing digit** is the one that closes most against the others, and of those
  alike, the one whose root lies furthest from the line through the others' roots (a
  thumb beside a row of fingers; the first of two jaws: :func:`_opposing`). Its motors
  before its closing run (a thumb's rotation and abduction) are set, before a grasp, to
  where closing brings its tip furthest towards the others' (``preshape``, see
  :func:`_preshape`); the others' stay at rest.
- **The hand faces** (``approach``) along its palm's thinnest axis, towards the side the
  tips close on; ``forward`` runs from the palm's centre towards the open tips, across it.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, replace
from typing import Any, Mapping, Sequence

import numpy as np

from ..kit.math3d import Pose, Vec3, rotate
from .articulation import NO_POSE, Articulation, Joint, Link
from .geometry import solid_points

SPAN = 1.5        # rad: how far a motor without limits is tried each way from rest
REACH = 0.5       # × the digit's length: how far a sliding motor without limits is tried
PARALLEL = 0.98   # |cos| between two joint axes that turn in one plane
OPEN_STEPS = 13   # values tried for a closing motor's open value
PRESHAPE_STEPS = 7  # values tried for each preshape motor, across its range
TIE = 0.05        # mean cosines this close count as closing against the others alike
DEPTH = 2.0       # what a preshape's tip depth differing from the others' by one unit costs
PRESHAPE_TRIES = 343  # at most this many preshapes tried together (three motors' grid)


@dataclass(frozen=True)
class DigitMotor:
    """A motor of a digit: its value with the digit open and closed."""

    motor: str
    open: float
    closed: float

    def at(self, share: float) -> float:
        """Its value ``share`` of the way from open (0) to closed (1)."""
        return self.open + (self.closed - self.open) * share


@dataclass(frozen=True)
class Digit:
    """A chain from the palm to a tip: the motors that close it (palm first); for the
    opposing digit, those that turn it to face the others before a grasp."""

    tip: str
    motors: tuple[DigitMotor, ...]
    opposes: bool = False
    preshape: tuple[DigitMotor, ...] = ()
    tip_at: Vec3 = (0.0, 0.0, 0.0)  # its far point, open and preshaped (the robot's frame)
    parts: tuple[str, ...] = ()     # the parts it moves (what it touches an object with)


@dataclass(frozen=True)
class GripMap:
    """A hand's digits and its palm (None: digits that hang from no part), and in the
    robot's own frame with the digits open and preshaped: the palm's centre, the way the
    hand faces (``approach``, towards what it grasps), the way from the palm to the tips
    (``forward``), where the tips meet half closed (``grasp``), and how far the palm and
    the whole hand reach from the centre along ``approach``, ``forward`` and ``side``
    (their cross product): ``palm`` and ``hand`` bounds, (low, high) each."""

    palm: str | None
    digits: tuple[Digit, ...]
    centre: Vec3
    approach: Vec3
    forward: Vec3
    grasp: Vec3
    palm_bounds: tuple[tuple[float, float], ...]
    hand_bounds: tuple[tuple[float, float], ...]

    def wire(self) -> dict[str, Any]:
        """As ``getGripMap`` answers it."""
        def motors(items: Sequence[DigitMotor]) -> list[dict[str, Any]]:
            return [{"motor": m.motor, "open": m.open, "closed": m.closed} for m in items]
        def bounds(of: Sequence[tuple[float, float]]) -> dict[str, list[float]]:
            return {axis: list(pair) for axis, pair in zip(("approach", "forward", "side"), of)}
        return {"palm": self.palm, "centre": list(self.centre), "approach": list(self.approach),
                "forward": list(self.forward), "grasp": list(self.grasp),
                "palmBounds": bounds(self.palm_bounds), "handBounds": bounds(self.hand_bounds),
                "digits": [{"tip": d.tip, "opposes": d.opposes, "motors": motors(d.motors),
                            "preshape": motors(d.preshape), "tipAt": list(d.tip_at),
                            "parts": list(d.parts)}
                           for d in self.digits]}


@dataclass
class _Chain:
    """A digit being derived: its tip's link, its closing and its preshape joints' links,
    the point of its tip furthest from its root (in the tip link's frame), its length."""

    tip: int
    closing: list[int]
    before: list[int]
    point: np.ndarray
    length: float


class _Hand:
    """The tree, its rest, and forward kinematics of a digit's far point."""

    def __init__(self, tree: Articulation, rest: Mapping[str, float]) -> None:
        self.tree, self.rest = tree, dict(rest)

    def tip(self, chain: _Chain, values: Mapping[str, float]) -> np.ndarray:
        return self.tips([chain], values)[0]

    def tips(self, chains: Sequence[_Chain], values: Mapping[str, float]) -> np.ndarray:
        """Where each digit's far point is with the motors at ``values`` (the rest at rest)."""
        poses = self.tree.link_poses({**self.rest, **values})
        return np.array([np.array(rotate(poses[c.tip][1], c.point)) + np.array(poses[c.tip][0])
                         for c in chains])


def grip_map(tree: Articulation, rest: Mapping[str, float]) -> GripMap:
    """The grip map of ``tree`` with its motors at ``rest`` (see the module's rules)."""
    hand, poses = _Hand(tree, rest), tree.link_poses(rest)
    palm = _palm(tree, _tips(tree))
    chains = [chain for chain in (_chain(tree, poses, tip, palm) for tip in _tips(tree)) if chain.closing]
    centre = _centre(tree, poses, palm, chains)
    closing = _closing(hand, chains, centre)
    opposing = _opposing(hand, poses, chains, closing)
    opened = {m.motor: m.open for motors in closing for m in motors}
    half = {m.motor: m.at(0.5) for motors in closing for m in motors}
    approach, _ = _facing(tree, hand, poses, palm, chains, opened, half, opposing)
    preshape = _preshape(hand, chains, closing, opposing, approach)
    if preshape:  # the opposing digit closes the other way once it faces the others
        turned = _Hand(tree, {**rest, **{m.motor: m.closed for m in preshape}})
        closing[opposing] = _closing(turned, [chains[opposing]], centre)[0]
        preshape = _preshape(hand, chains, closing, opposing, approach)
    digits = tuple(Digit(tree.links[chain.tip].part or "", tuple(closing[i]), i == opposing,
                         preshape if i == opposing else (), parts=_moved(tree, chain))
                   for i, chain in enumerate(chains))
    return _laid_out(hand, palm, chains, digits)


def _laid_out(hand: _Hand, palm: int, chains: list[_Chain], digits: tuple[Digit, ...]) -> GripMap:
    """The map of ``digits``, measured with them open and preshaped."""
    tree = hand.tree
    ready = {**{m.motor: m.open for d in digits for m in d.motors},
             **{m.motor: m.closed for d in digits for m in d.preshape}}
    poses = tree.link_poses({**hand.rest, **ready})
    centre = _centre(tree, poses, palm, chains)
    opposing = next((i for i, d in enumerate(digits) if d.opposes), -1)
    half = {m.motor: m.at(0.5) for d in digits for m in d.motors}
    approach, forward = _facing(tree, hand, poses, palm, chains, ready, half, opposing)
    axes = np.array([approach, forward, np.cross(approach, forward)])
    palm_points = _palm_points(tree, poses, palm)
    base = [] if tree.base_geometry is None else [_palm_points(tree, poses, -1)]
    every = np.concatenate([_placed(pose, _shape_points(link)) for pose, link in zip(poses, tree.links)]
                           + base)
    grasp = hand.tips(chains, {**ready, **half}).mean(axis=0) if chains else centre
    at = hand.tips(chains, ready) if chains else np.zeros((0, 3))
    digits = tuple(replace(digit, tip_at=_vec(tip)) for digit, tip in zip(digits, at))
    return GripMap(tree.base_part if palm < 0 else tree.links[palm].part, digits, _vec(centre), _vec(approach), _vec(forward), _vec(grasp),
                   _bounds(palm_points if palm_points is not None else centre[None], centre, axes),
                   _bounds(every, centre, axes))


def _bounds(points: np.ndarray, centre: np.ndarray, axes: np.ndarray) -> tuple[tuple[float, float], ...]:
    """How far ``points`` reach from ``centre`` along each of ``axes`` (low, high)."""
    along = (points - centre) @ axes.T
    return tuple((float(low), float(high)) for low, high in zip(along.min(axis=0), along.max(axis=0)))


def _path(tree: Articulation, link: int) -> list[int]:
    """The links from below the base down to ``link``."""
    path = []
    while link >= 0:
        path.append(link)
        link = tree.links[link].parent
    return path[::-1]


def _tips(tree: Articulation) -> list[int]:
    """Links with a part, no part below them, and a joint above them."""
    above_parts = {k for j, link in enumerate(tree.links) if link.part is not None
                   for k in _path(tree, j)[:-1]}
    return [k for k, link in enumerate(tree.links) if link.part is not None
            and k not in above_parts and any(tree.links[j].joint for j in _path(tree, k))]


def _palm(tree: Articulation, tips: list[int]) -> int:
    """The deepest part-carrying link (−1: the base) above the first joint of every tip."""
    shared: list[int] | None = None
    for tip in tips:
        path = [-1] + _path(tree, tip)
        first = next(i for i, k in enumerate(path) if k >= 0 and tree.links[k].joint is not None)
        shared = path[:first] if shared is None else [k for k in shared if k in path[:first]]
    carrying = [k for k in (shared or [-1]) if k < 0 or tree.links[k].part is not None]
    return carrying[-1] if carrying else -1


def _chain(tree: Articulation, poses: list[Pose], tip: int, palm: int) -> _Chain:
    """A tip's digit: its joints below the palm, split into the closing run at its end
    and those before it, and its tip's far point."""
    path = _path(tree, tip)
    joints = [k for k in (path[path.index(palm) + 1:] if palm in path else path)
              if tree.links[k].joint is not None]
    if not joints:
        return _Chain(tip, [], [], np.zeros(3), 0.0)
    axes = [np.array(rotate(poses[k][1], tree.links[k].joint.axis)) for k in joints]  # type: ignore[union-attr]
    run = len(joints) - 1
    while run > 0 and abs(float(np.dot(axes[run - 1], axes[-1]))) >= PARALLEL:
        run -= 1
    root = np.array(poses[joints[0]][0])
    local = _shape_points(tree.links[tip])
    world = _placed(poses[tip], local)
    far = int(np.argmax(np.linalg.norm(world - root, axis=1)))
    return _Chain(tip, joints[run:], joints[:run], local[far], float(np.linalg.norm(world[far] - root)))


def _moved(tree: Articulation, chain: _Chain) -> tuple[str, ...]:
    """The parts on a digit's way from its first joint to its tip."""
    first = (chain.before or chain.closing)[0]
    path = _path(tree, chain.tip)
    return tuple(tree.links[k].part for k in path[path.index(first):]  # type: ignore[misc]
                 if tree.links[k].part is not None)


def _shape_points(link: Link) -> np.ndarray:
    """The corners of a link's part, in the link's frame."""
    geometry = link.geometry
    if geometry is None:
        return np.zeros((1, 3))
    if geometry["kind"] == "box":
        corners = np.array(list(itertools.product((-0.5, 0.5), repeat=3)))
        points = corners * np.array(geometry["size"])
    else:
        points = np.asarray(solid_points(geometry), float)
    return _placed(link.shape, points)


def _placed(pose: Pose, points: np.ndarray) -> np.ndarray:
    return np.array([rotate(pose[1], p) for p in points]) + np.array(pose[0])


def _palm_points(tree: Articulation, poses: list[Pose], palm: int) -> np.ndarray | None:
    if palm >= 0:
        return _placed(poses[palm], _shape_points(tree.links[palm]))
    if tree.base_geometry is None:
        return None
    return _shape_points(Link(-1, NO_POSE, None, None, geometry=tree.base_geometry))


def _centre(tree: Articulation, poses: list[Pose], palm: int, chains: list[_Chain]) -> np.ndarray:
    """The palm's middle: its part's box's (a mesh's points crowd where it is curved),
    else the digits' roots'."""
    points = _palm_points(tree, poses, palm)
    if points is not None:
        return (points.min(axis=0) + points.max(axis=0)) / 2
    roots = [poses[(chain.before or chain.closing)[0]][0] for chain in chains]
    return np.mean(roots, axis=0) if roots else np.zeros(3)


def _opposing(hand: _Hand, poses: list[Pose], chains: list[_Chain],
              closing: list[list[DigitMotor]]) -> int:
    """The digit whose tip closes most against the others' (the least mean cosine of its
    closing motion with theirs: a thumb's curls across the fingers'); of digits within
    :data:`TIE` of that, the one whose root lies furthest from the line through the
    others' roots (a thumb beside a row of fingers). −1: fewer than two digits."""
    if len(chains) < 2:
        return -1
    ends = [{m.motor: getattr(m, end) for motors in closing for m in motors} for end in ("open", "closed")]
    moves = hand.tips(chains, ends[1]) - hand.tips(chains, ends[0])
    moves = moves / np.maximum(np.linalg.norm(moves, axis=1, keepdims=True), 1e-12)
    against = [float(np.mean(np.delete(moves, i, axis=0) @ move)) for i, move in enumerate(moves)]
    candidates = [i for i, value in enumerate(against) if value <= min(against) + TIE]
    roots = np.array([poses[(chain.before or chain.closing)[0]][0] for chain in chains])
    apart = []
    for index, root in enumerate(roots):
        others = np.delete(roots, index, axis=0)
        offset = root - others.mean(axis=0)
        if len(others) > 1:
            direction = np.linalg.svd(others - others.mean(axis=0))[2][0]
            offset = offset - direction * float(np.dot(offset, direction))
        apart.append(float(np.linalg.norm(offset)))
    return max(candidates, key=lambda i: apart[i])


def _closing(hand: _Hand, chains: list[_Chain], centre: np.ndarray) -> list[list[DigitMotor]]:
    """Each digit's closing motors, open and closed."""
    return [[_ends(hand, chain, link, centre) for link in chain.closing] for chain in chains]


def _ends(hand: _Hand, chain: _Chain, link: int, centre: np.ndarray) -> DigitMotor:
    """A closing motor's open and closed values (see the module's rules)."""
    joint = hand.tree.links[link].joint
    assert joint is not None
    ends = _range(joint, hand.rest.get(joint.motor, 0.0), chain.length)
    scores = [float(np.linalg.norm(hand.tip(chain, {joint.motor: value}) - centre)) for value in ends]
    closed = 0 if scores[0] < scores[1] else 1
    # open: straightest, where the tip is furthest from the palm's centre
    values = np.linspace(ends[1 - closed], ends[closed], OPEN_STEPS)
    far = max(values, key=lambda value: float(np.linalg.norm(hand.tip(chain, {joint.motor: value}) - centre)))
    return DigitMotor(joint.motor, float(far), float(ends[closed]))


def _range(joint: Joint, rest: float, length: float) -> tuple[float, float]:
    """The values a motor is tried between: its limits, within a half turn of its rest;
    without limits, :data:`SPAN` (a slider: :data:`REACH` of its digit's length) each way."""
    if joint.slides:
        span, far = REACH * length, math.inf
    else:
        span, far = SPAN, math.pi
    low = max(joint.lower, rest - far) if math.isfinite(joint.lower) else rest - span
    high = min(joint.upper, rest + far) if math.isfinite(joint.upper) else rest + span
    return low, high


def _facing(tree: Articulation, hand: _Hand, poses: list[Pose], palm: int, chains: list[_Chain],
            opened: Mapping[str, float], half: Mapping[str, float],
            opposing: int) -> tuple[np.ndarray, np.ndarray]:
    """``approach`` and ``forward`` with the digits open (see the module's rules)."""
    centre = _centre(tree, poses, palm, chains)
    ahead = [chain for i, chain in enumerate(chains) if i != opposing] or chains
    open_tips = hand.tips(ahead, opened) if ahead else np.zeros((1, 3))
    # half closed: curled fully, a long digit's tip comes back up past its palm
    half_tips = hand.tips(chains, {**opened, **half}) if chains else open_tips
    side = half_tips.mean(axis=0) - centre
    points = _palm_points(tree, poses, palm)
    if points is not None and len(points) >= 4:
        approach = np.linalg.svd(points - points.mean(axis=0))[2][-1]  # the thinnest axis
    else:
        approach = _unit(side)
    approach = approach if float(np.dot(approach, side)) >= 0 else -approach
    ahead = open_tips.mean(axis=0) - centre
    forward = ahead - approach * float(np.dot(ahead, approach))
    if np.linalg.norm(forward) < 0.3 * np.linalg.norm(ahead):  # tips ahead of the palm: a gripper
        forward = _gripper_forward(hand, chains, opened, opposing, approach)
    return _unit(approach), _unit(forward)


def _gripper_forward(hand: _Hand, chains: list[_Chain], opened: Mapping[str, float], opposing: int,
                     approach: np.ndarray) -> np.ndarray:
    """A gripper's ``forward``: from its opposing digit towards the others (as a hand's
    thumb wraps from the wrist's side), across ``approach``; any such way without one."""
    way = np.zeros(3)
    if opposing >= 0 and len(chains) > 1:
        tips = hand.tips(chains, opened)
        way = np.delete(tips, opposing, axis=0).mean(axis=0) - tips[opposing]
    way = way - approach * float(np.dot(way, approach))
    if np.linalg.norm(way) < 1e-9:
        way = np.cross(approach, [1.0, 0.0, 0.0] if abs(approach[0]) < 0.9 else [0.0, 1.0, 0.0])
    return way


def _preshape(hand: _Hand, chains: list[_Chain], closing: list[list[DigitMotor]], opposing: int,
              approach: np.ndarray) -> tuple[DigitMotor, ...]:
    """The opposing digit's motors before its closing run, where closing half way (round
    an object of some size) brings its tip furthest towards the others' tips, and as deep
    below the palm as theirs (a thumb that curls beside the palm, not round the object,
    has its tip high), and open, hanging no deeper than theirs (it would meet the table
    first): :data:`DEPTH` weighs both (open: their rest)."""
    if opposing < 0 or not chains[opposing].before:
        return ()
    ends = [{m.motor: m.at(share) for motors in closing for m in motors} for share in (0.0, 0.5)]
    chain, choices = chains[opposing], []
    for link in chain.before:
        joint = hand.tree.links[link].joint
        assert joint is not None
        low, high = _range(joint, hand.rest.get(joint.motor, 0.0), chain.length)
        choices.append([(joint.motor, v) for v in np.linspace(low, high, PRESHAPE_STEPS)])
    def apart(values: Mapping[str, float], end: Mapping[str, float]) -> np.ndarray:
        tips = hand.tips(chains, {**end, **values})
        return np.asarray(tips[opposing] - np.delete(tips, opposing, axis=0).mean(axis=0))

    def sweep(values: Mapping[str, float]) -> float:
        opened, half = apart(values, ends[0]), apart(values, ends[1])
        return float(np.linalg.norm(opened) - np.linalg.norm(half)
                     - DEPTH * (abs(float(np.dot(half, approach))) + max(0.0, float(np.dot(opened, approach)))))
    if PRESHAPE_STEPS ** len(choices) <= PRESHAPE_TRIES:
        best = max(itertools.product(*choices), key=lambda values: sweep(dict(values)))
    else:  # each motor in turn, twice over: the whole grid would be too long a stall
        best = tuple(options[len(options) // 2] for options in choices)
        for _ in range(2):
            for k, options in enumerate(choices):
                best = max((best[:k] + (option,) + best[k + 1:] for option in options),
                           key=lambda values: sweep(dict(values)))
    return tuple(DigitMotor(motor, hand.rest.get(motor, 0.0), float(value)) for motor, value in best)


def _unit(v: np.ndarray) -> np.ndarray:
    size = float(np.linalg.norm(v))
    return v / size if size > 0 else v


def _vec(v: Any) -> Vec3:
    return (float(v[0]), float(v[1]), float(v[2]))
