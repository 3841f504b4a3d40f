"""Dynamic mode: in a crowd, free bodies at rest far from anything that moves are held
still as static bodies until something moving comes near.

Bullet sleeps a whole island at once, and a heap is one island: blocks resting on each
other link through their contacts whatever lies under them, so a hand that touches one
block of the Box and Blocks heap each second keeps all 150 awake, and the solver works
every contact of the heap every step (2.4 CPU-seconds per scene-second for a heap at
rest; 0.006 asleep). Here each body rests on its own: a single free body (no links) that
moved slower than REST_SPEED and turned slower than REST_SPIN for CALM seconds, and lies
beyond ROBOT_MARGIN of every robot's link and MARGIN of every free body moving faster
than STIR_SPEED, becomes static in Bullet (a fixed base, mass 0: Bullet's own switch,
``changeDynamics``), in RESTING_GROUP, which meets moving bodies and robots but not the
ground or other resting bodies: Bullet then neither pairs nor solves the heap's resting
contacts. When a robot's link comes within ROBOT_MARGIN, or a moving body within MARGIN
and the distance it travels in LOOKAHEAD, a resting body gets its mass, inertia and group
back before the next step, so whatever touches it meets a body that moves; so does one
that a robot, or a body not at rest, pressed on with more than PRESSED times its weight
(pushed too slowly to stir it). A body put somewhere by a script, and the bodies near one
taken away, move again at once.

No library does this: Bullet's deactivation is per island (above), and PyBullet offers
no per-body freezing beyond the fixed base used here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Iterable

from .filter_groups import BODY_GROUP, BODY_MASK, RESTING_GROUP, RESTING_MASK

Box = tuple[float, float, float, float, float, float]  # Bullet's: low x, y, z, high x, y, z
Link = tuple[int, int]  # a body and a link of it (-1: its base)

# free bodies past which resting ones are held still: below it the review costs about
# what it saves (10 animated hands in dynamic mode ticked alike with 10 or 20 objects at
# rest, held still or not); past it the heap's resting contacts cost the solver more (32
# objects: 1 ms a tick less held still, 50: 2.3 ms of 18)
CROWD = 24
REST_SPEED = 0.01   # m/s: slower than this a body is at rest ...
REST_SPIN = 0.2     # rad/s: ... turning slower than this ...
CALM = 0.25         # s: ... for this long
STIR_SPEED = 0.05  # m/s: a body faster than this moves those it comes near
MARGIN = 0.01       # m: a moving body holds nothing still this near it ...
ROBOT_MARGIN = 0.02  # m: ... and a robot's link nothing this near (a block's size: a hand
# taking a block from a heap moves those beside it). The Box and Blocks baseline (edged
# hand, seeds 1-6) moved 5.8 blocks a minute on average with nothing held still, 4.8 with
# this (4.5 with 0.01, 4.2 with 0.03, 4.3 letting move what touches what a hand touches;
# one seed's count changes by ±2 with any change, even of rounding)
LOOKAHEAD = 2 / 60  # s: and a moving body's box is widened by how far it goes in this
PRESSED = 10.0  # × its weight: a held body pressed harder than this moves again (a block
# squeezed by a finger into its held neighbours pressed them with 5-32 times their weight;
# at 2 or 5 a ball of eight blocks' weight dropped on a heap moved blocks 3 blocks away)
# pressers past this many: the world's contact points read at once (each body's own is a
# pass of Bullet's over every contact manifold)
ASKED_ONE_BY_ONE = 16


@dataclass
class _Held:
    """A body held still: what it gets back, and its box (Bullet's, kept: it does not move)."""

    mass: float
    inertia: tuple[float, float, float]
    box: Box


class Resting:
    """The resting free bodies of one dynamic world (``unit``: metres per scene unit)."""

    def __init__(self, pybullet: Any, client: int, unit: float, gravity: float = 0.0) -> None:
        self.p, self.client = pybullet, client
        self._gravity = abs(gravity)  # in Bullet's units (a held body's weight: PRESSED)
        self._speed, self._stir, self._margin = REST_SPEED / unit, STIR_SPEED / unit, MARGIN / unit
        self._robot_margin = ROBOT_MARGIN / unit
        self.free: set[int] = set()   # single free bodies (those that may rest)
        self._calm: dict[int, float] = {}  # awake free body -> seconds it has been at rest
        self.held: dict[int, _Held] = {}
        self._gone: list[Box] = []  # boxes of bodies taken away since the last review

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
        if len(self.free) <= CROWD:
            thawing = list(self.held)
        else:
            movers, reach = self._moving_boxes(seconds)
            asked = list(self.held) + [b for b, rested in self._calm.items() if rested >= CALM]
            boxes = self._boxes(asked)
            robots = list(robots)
            p, client = self.p, self.client
            links = sum(p.getNumJoints(robot, physicsClientId=client) + 1 for robot in robots)
            # robots' links as movers (a box read each) or from the bodies' side (a
            # broadphase question each), whichever is fewer: ten hands' 210 boxes read
            # every tick were a tenth of their dynamic tick's Python
            if links <= len(boxes):
                movers.update(self._robot_boxes(robots))
                near = self._near(movers, reach, boxes)
            else:
                near = self._near(movers, reach, boxes) | self._near_robots(set(robots), boxes)
            near |= self._pressed(set(robots))
            thawing = [body for body in self.held if body in near]
            for body in asked[len(self.held):]:
                if body not in near:
                    self._freeze(body)
        for body in thawing:
            self._thaw(body)
        return bool(thawing)

    def _pressed(self, robots: set[int]) -> set[int]:
        """The held bodies that a robot, or a free body not at rest, pressed on in the last
        step with more than PRESSED times their weight: pushed by what moves too slowly to
        stir them (a block squeezed by a finger into its held neighbours), a held body
        stands firm as a wall would, the solver sinks what presses into it, and it springs
        out when it moves again (a finger sweeping one row of a heap moved rows four
        blocks away; Bullet's own world, nothing held, moved none of them). What rests on a
        held body moves nothing: a block thawed in a heap, pressed by what lies on it,
        would thaw those under it, and they those beside them."""
        held, found = self.held, set()
        if not held or not self._gravity:
            return found
        pressers = robots | {body for body, rested in self._calm.items() if rested == 0.0}
        for a, b, force in self._contacts_of(pressers):
            for mine, other in ((a, b), (b, a)):
                if mine in held and other in pressers and \
                        force > PRESSED * held[mine].mass * self._gravity:
                    found.add(mine)
        return found

    def _contacts_of(self, bodies: set[int]) -> Iterable[tuple[int, int, float]]:
        """(body, body, normal force) of the last step's contact points, at least those of
        ``bodies``: Bullet asked for each of a few bodies' own (a hand in a held heap of
        150 blocks: every point of the world gone through in Python was 5 % of Box and
        Blocks' scene process), else for every point at once."""
        p, client = self.p, self.client
        if len(bodies) > ASKED_ONE_BY_ONE:
            points = p.getContactPoints(physicsClientId=client)
        else:
            points = [point for body in bodies
                      for point in p.getContactPoints(bodyA=body, physicsClientId=client)]
        return ((point[1], point[2], point[9]) for point in points)

    def _boxes(self, bodies: list[int]) -> dict[int, Box]:
        """The boxes of these bodies: a held one's as kept, an awake one's now."""
        return {body: self.held[body].box if body in self.held else self._box(body) for body in bodies}

    def _near(self, movers: dict[Link, Box], reach: float, boxes: dict[int, Box]) -> set[int]:
        """Which of the bodies whose ``boxes`` are given overlap a box of what moves (each
        widened by at most ``reach`` beyond the body or link's own box). Bullet's
        broadphase names the candidates, a few µs a box, from whichever side is smaller:
        every body tested against every box took a third of a 2 000-ball pile's process."""
        ask, client, near = self.p.getOverlappingObjects, self.client, set()
        if len(movers) <= len(boxes):
            for mover in movers.values():
                found = ask(mover[:3], mover[3:], physicsClientId=client) or ()
                near.update(body for body, _ in found if body in boxes and _overlap(boxes[body], mover))
            return near
        gone = [box for key, box in movers.items() if key[0] < 0]  # (in no broadphase)
        for body, box in boxes.items():
            wide = _widened(box, reach)
            found = ask(wide[:3], wide[3:], physicsClientId=client) or ()
            if any(key in movers and _overlap(box, movers[key]) for key in found) or \
                    any(_overlap(box, mover) for mover in gone):
                near.add(body)
        return near

    def _near_robots(self, robots: set[int], boxes: dict[int, Box]) -> set[int]:
        """Which of the bodies whose ``boxes`` are given lie within ROBOT_MARGIN of a link
        of ``robots``: the broadphase's boxes hold Bullet's own (they are wider by the
        contact threshold), so it names every candidate link, whose box is then read."""
        ask, client, near, margin = self.p.getOverlappingObjects, self.client, set(), self._robot_margin
        for body, box in boxes.items():
            wide = _widened(box, margin)
            for other, link in ask(wide[:3], wide[3:], physicsClientId=client) or ():
                if other in robots and _overlap(box, _widened(self._box(other, link), margin)):
                    near.add(body)
                    break
        return near

    def _robot_boxes(self, robots: list[int]) -> dict[Link, Box]:
        """The box of every link of ``robots``, widened by ROBOT_MARGIN."""
        p, client, margin = self.p, self.client, self._robot_margin
        return {(robot, link): _widened(self._box(robot, link), margin)
                for robot in robots for link in range(-1, p.getNumJoints(robot, physicsClientId=client))}

    def _moving_boxes(self, seconds: float) -> tuple[dict[Link, Box], float]:
        """The boxes of every awake free body that moves (widened by MARGIN and the way
        it goes in LOOKAHEAD) and of the bodies taken away (by MARGIN; keyed -1, -2 …),
        and the most any box may be widened (robots' links' included); each body's time
        at rest counted on."""
        p, client = self.p, self.client
        boxes = {(-1 - k, -1): _widened(box, self._margin) for k, box in enumerate(self._gone)}
        self._gone = []
        rest, spin, stir = self._speed ** 2, REST_SPIN ** 2, self._stir ** 2
        reach = max(self._margin, self._robot_margin)
        for body in self._calm:
            (vx, vy, vz), (wx, wy, wz) = p.getBaseVelocity(body, physicsClientId=client)
            speed = vx * vx + vy * vy + vz * vz
            if speed < rest and wx * wx + wy * wy + wz * wz < spin:
                self._calm[body] += seconds
                continue
            self._calm[body] = 0.0
            if speed >= stir:
                way = self._margin + math.sqrt(speed) * LOOKAHEAD
                boxes[body, -1] = _widened(self._box(body), way)
                reach = max(reach, way)
        return boxes, reach

    def _box(self, body: int, link: int = -1) -> Box:
        low, high = self.p.getAABB(body, link, physicsClientId=self.client)
        return (*low, *high)

    def _freeze(self, body: int) -> None:
        p, client = self.p, self.client
        mass, _, inertia = p.getDynamicsInfo(body, -1, physicsClientId=client)[:3]
        self.held[body] = _Held(mass, tuple(inertia), self._box(body))
        del self._calm[body]
        p.resetBaseVelocity(body, (0, 0, 0), (0, 0, 0), physicsClientId=client)
        p.changeDynamics(body, -1, mass=0.0, physicsClientId=client)
        # Bullet gives a body made static its own static group: it would meet nothing of ours
        p.setCollisionFilterGroupMask(body, -1, RESTING_GROUP, RESTING_MASK, physicsClientId=client)

    def _thaw(self, body: int) -> None:
        p, client = self.p, self.client
        held = self.held.pop(body)
        # (its sleeping, where the world lets bodies sleep, is Bullet's: what touches it wakes it)
        p.changeDynamics(body, -1, mass=held.mass, localInertiaDiagonal=held.inertia,
                         physicsClientId=client)
        p.setCollisionFilterGroupMask(body, -1, BODY_GROUP, BODY_MASK, physicsClientId=client)
        self._calm[body] = 0.0


def _overlap(a: Box, b: Box) -> bool:
    return a[0] <= b[3] and a[1] <= b[4] and a[2] <= b[5] and a[3] >= b[0] and a[4] >= b[1] and a[5] >= b[2]


def _widened(box: Box, by: float) -> Box:
    lx, ly, lz, hx, hy, hz = box
    return (lx - by, ly - by, lz - by, hx + by, hy + by, hz + by)
