"""Dynamic mode: in a crowd, free bodies at rest far from anything that moves are held
still as static bodies until something moving comes near.

Bullet sleeps a whole island at once, and a heap is one island: blocks resting on each
other link through their contacts whatever lies under them, so a hand that touches one
block of the Box and Blocks heap each second keeps all 150 awake, and the solver works
every contact of the heap every step (2.4 CPU-seconds per scene-second for a heap at
rest; 0.006 asleep). Here each body rests on its own: a single free body (no links) that
moved slower than REST_SPEED and turned slower than REST_SPIN for CALM seconds, and lies
beyond MARGIN of every robot's link and every moving free body, becomes static in Bullet
(a fixed base, mass 0: Bullet's own switch, ``changeDynamics``), in RESTING_GROUP, which
meets moving bodies and robots but not the ground or other resting bodies: Bullet then
neither pairs nor solves the heap's resting contacts. When a robot's link or a moving
body comes within MARGIN (and the distance it travels in LOOKAHEAD), a resting body gets
its mass, inertia and group back before the next step, so whatever touches it meets a
body that moves. A body put somewhere by a script, and the bodies near one taken away,
move again at once.

No library does this: Bullet's deactivation is per island (above), and PyBullet offers
no per-body freezing beyond the fixed base used here.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable

import numpy as np

from .filter_groups import BODY_GROUP, BODY_MASK, RESTING_GROUP, RESTING_MASK

CROWD = 64          # free bodies past which resting ones are held still
REST_SPEED = 0.01   # m/s: slower than this a body is at rest ...
REST_SPIN = 0.2     # rad/s: ... turning slower than this ...
CALM = 0.25         # s: ... for this long
STIR_SPEED = 0.05  # m/s: a body faster than this moves those it comes near
MARGIN = 0.01       # m: a moving body holds nothing still this near it ...
ROBOT_MARGIN = 0.02  # m: ... and a robot's link nothing this near (a block's size: a hand
# taking a block from a heap moves those beside it). The Box and Blocks baseline (edged
# hand, seeds 1-6) moved 5.8 blocks a minute on average with nothing held still; 5.8 with
# this, 4.5 with 0.01 and 4.2 with 0.03 (one seed's count varies by ±2 with any change)
LOOKAHEAD = 2 / 60  # s: and a moving body's box is widened by how far it goes in this


@dataclass
class _Held:
    """A body held still: what it gets back, and its box (Bullet's, kept: it does not move)."""

    mass: float
    inertia: tuple[float, float, float]
    box: np.ndarray


class Resting:
    """The resting free bodies of one dynamic world (``unit``: metres per scene unit)."""

    def __init__(self, pybullet: Any, client: int, unit: float) -> None:
        self.p, self.client = pybullet, client
        self._speed, self._stir, self._margin = REST_SPEED / unit, STIR_SPEED / unit, MARGIN / unit
        self._robot_margin = (ROBOT_MARGIN - MARGIN) / unit  # (widening a link's box)
        self.free: set[int] = set()   # single free bodies (those that may rest)
        self._calm: dict[int, float] = {}  # awake free body -> seconds it has been at rest
        self.held: dict[int, _Held] = {}
        self._boxes: tuple[list[int], np.ndarray] | None = None  # the held bodies' boxes
        self._gone: list[np.ndarray] = []  # boxes of bodies taken away since the last review

    def add(self, body: int) -> None:
        """A single free body made (it may rest from now on)."""
        self.free.add(body)
        self._calm[body] = 0.0

    def removed(self, body: int) -> None:
        """A free body taken away: those it may have held up move again at the review."""
        if body not in self.free:
            return
        self.free.discard(body)
        self._calm.pop(body, None)
        held = self.held.pop(body, None)
        self._boxes = None
        self._gone.append(held.box if held is not None else self._box(body))

    def release(self, body: int) -> None:
        """Let ``body`` move again now (a script puts it somewhere)."""
        if body in self.held:
            self._thaw(body)
        if body in self._calm:
            self._calm[body] = 0.0

    def review(self, seconds: float, robots: Iterable[int]) -> bool:
        """After steps of ``seconds``: hold still the free bodies at rest far from what
        moves, and let move those that something moving came near (``robots``: the bodies
        with parts that move other than single free ones: robots, free trees with joints);
        whether any may move again (the world is not at rest, though nothing moved yet)."""
        movers: np.ndarray | None = None
        if len(self.free) <= CROWD:
            thawing = list(self.held)
        else:
            movers = self._moving_boxes(seconds, robots)
            thawing = self._near_held(movers)
        for body in thawing:
            self._thaw(body)
        if movers is not None:
            self._freeze_calm(movers)
        return bool(thawing)

    def _near_held(self, movers: np.ndarray) -> list[int]:
        """The held bodies that something moving came near."""
        if not self.held or not len(movers):
            return []
        if self._boxes is None:  # (made again only when a body is held or let go)
            self._boxes = list(self.held), np.array([self.held[body].box for body in self.held])
        held, boxes = self._boxes
        return [held[k] for k in np.nonzero(_near(boxes, movers, self._margin))[0]]

    def _freeze_calm(self, movers: np.ndarray) -> None:
        """Hold still the bodies at rest for CALM that nothing moving is near."""
        calm = [body for body, rested in self._calm.items() if rested >= CALM]
        if not calm:
            return
        boxes = np.array([self._box(body) for body in calm])
        near = _near(boxes, movers, self._margin) if len(movers) else np.zeros(len(calm), bool)
        for body, box, touched in zip(calm, boxes, near):
            if not touched:
                self._freeze(body, box)

    def _moving_boxes(self, seconds: float, robots: Iterable[int]) -> np.ndarray:
        """The boxes of every robot link, of every awake free body that moves (widened by
        the way it goes in LOOKAHEAD), and of the bodies taken away; each body's time at
        rest counted on."""
        p, client = self.p, self.client
        boxes = self._gone
        self._gone = []
        reach = np.array([-self._robot_margin] * 3 + [self._robot_margin] * 3)
        for robot in robots:
            for link in range(-1, p.getNumJoints(robot, physicsClientId=client)):
                boxes.append(self._box(robot, link) + reach)
        for body in self._calm:
            linear, angular = p.getBaseVelocity(body, physicsClientId=client)
            speed = float(np.linalg.norm(linear))
            if speed < self._speed and float(np.linalg.norm(angular)) < REST_SPIN:
                self._calm[body] += seconds
                continue
            self._calm[body] = 0.0
            if speed < self._stir:
                continue
            box = self._box(body)
            reach = speed * LOOKAHEAD
            boxes.append(box + np.array([-reach] * 3 + [reach] * 3))
        return np.array(boxes).reshape(-1, 6)

    def _box(self, body: int, link: int = -1) -> np.ndarray:
        low, high = self.p.getAABB(body, link, physicsClientId=self.client)
        return np.array([*low, *high])

    def _freeze(self, body: int, box: np.ndarray) -> None:
        p, client = self.p, self.client
        mass, _, inertia = p.getDynamicsInfo(body, -1, physicsClientId=client)[:3]
        self.held[body] = _Held(mass, tuple(inertia), box)
        self._boxes = None
        del self._calm[body]
        p.resetBaseVelocity(body, (0, 0, 0), (0, 0, 0), physicsClientId=client)
        p.changeDynamics(body, -1, mass=0.0, physicsClientId=client)
        # Bullet gives a body made static its own static group: it would meet nothing of ours
        p.setCollisionFilterGroupMask(body, -1, RESTING_GROUP, RESTING_MASK, physicsClientId=client)

    def _thaw(self, body: int) -> None:
        p, client = self.p, self.client
        held = self.held.pop(body)
        self._boxes = None
        # (its sleeping, where the world lets bodies sleep, is Bullet's: what touches it wakes it)
        p.changeDynamics(body, -1, mass=held.mass, localInertiaDiagonal=held.inertia,
                         physicsClientId=client)
        p.setCollisionFilterGroupMask(body, -1, BODY_GROUP, BODY_MASK, physicsClientId=client)
        self._calm[body] = 0.0


def _near(boxes: np.ndarray, movers: np.ndarray, margin: float) -> np.ndarray:
    """For each box (n × 6: low, high), whether it comes within ``margin`` of any mover's."""
    low, high = boxes[:, None, :3], boxes[:, None, 3:]
    apart = (low - margin > movers[None, :, 3:]) | (high + margin < movers[None, :, :3])
    return (~apart.any(axis=2)).any(axis=1)
