"""Dynamic mode: free bodies put inside others are moved to the nearest clear spot first.

Bullet's multibody solver grows its arrays one contact at a time, each growth a copy
of the whole array (``btAlignedObjectArray::resize`` reserves exactly what is asked),
so the first step after n bodies appear in one spot costs about n⁴: 80 balls of radius
0.2 made at one point took 0.9 s of one step, 160 took 16 s, and 300 never finished a
tick. Their pairs (n²/2) alone would take gigabytes. So a free body that is made, or put
by a script, deep inside another free or static body goes to the nearest spot where it
is inside nothing (searched on a lattice of its own size around where it was put, the
nearest first, upward before downward), before the solver sees it: a pile made in one
batch becomes a heap of bodies side by side that falls and settles. Touching and shallow
overlaps (less than DEEP of the body's thinnest half-size) are left to the solver, which
pushes such bodies apart gently.

No library does this: Bullet has no "place without overlap". Its broadphase tells what is
near a spot (a few µs a question); the links of bodies made since the last step may not be
where its boxes say yet, so those are also kept in a grid of the search's own until the
next step (rebuilding a grid of every body at each step cost 15 ms a tick among 1 000).
"""

from __future__ import annotations

import math
from functools import cache
from itertools import product
from typing import Any, Callable, Iterator

from ..kit.math3d import Vec3

Box = tuple[Vec3, Vec3]
DEEP = 0.25  # of the arriving body's thinnest half-size: deeper overlaps are moved out
REACH = 10  # lattice steps searched each way (21³ spots: room for thousands in one spot)
GAP = 1.02  # lattice spacing, in the body's own box sizes: side by side, not touching
SLACK = 0.05  # m: how far a body may have moved since the broadphase took its box


class Clearance:
    """Places free bodies clear of others in one dynamic world (``robots()``: the bodies
    that are robots; ``ground``: the ground's body)."""

    def __init__(self, pybullet: Any, client: int, robots: Callable[[], set[int]],
                 steps: Callable[[], int], ground: int) -> None:
        self.p, self.client, self._robot_bodies, self._steps = pybullet, client, robots, steps
        self._ground = ground
        self._fresh: _Grid | None = None  # bodies placed since the last step
        self._fresh_steps = -1  # the world's steps when they began to be placed
        self._robots: set[int] = set()
        self._searches: dict[tuple[Any, ...], Iterator[Vec3]] = {}
        self._searching: set[tuple[Any, ...]] = set()  # searches used since the last step
        self.moved = 0  # bodies moved out of others, ever

    def removed(self, body: int) -> None:
        if self._fresh is not None:
            self._fresh.remove(body)

    def place(self, body: int, position: Vec3, orientation: Any) -> bool:
        """Leave the free ``body``, just made or put at a pose (its centre of mass's), where
        it is, or, if it is deep inside a free or static body there (not a robot: a hand
        closes on what it is given), move it to the nearest clear spot; True if it moved."""
        fresh = self._fresh_without(body)
        box = self._box(body)
        depth = DEEP * min(high - low for low, high in zip(*box)) / 2
        moved = False
        if self._inside(body, box, fresh, depth, skip=self._robots, ground=False):
            spot = self._clear_spot(body, box, position, orientation, fresh, depth)
            if spot is not None:
                box, moved = _shifted(box, spot), True
                self.moved += 1
        fresh.add(body, box)
        return moved

    def _fresh_without(self, body: int) -> _Grid:
        """The bodies placed since the world last stepped, ``body`` left out (a new grid
        once it has stepped since)."""
        if self._fresh is None or self._fresh_steps != self._steps():
            # a search goes on where it was only while bodies keep coming to its spot (a
            # batch built over several ticks), else it starts again from the spot itself:
            # started again at each tick, 2 000 balls in 10 ticks tested 900 000 spots
            self._fresh_steps = self._steps()
            self._searches = {key: self._searches[key] for key in self._searching}
            self._searching = set()
            self._robots = self._robot_bodies()
            self._fresh = _Grid(max(max(high - low for low, high in zip(*self._box(body))), 1e-3))
        else:
            self._fresh.remove(body)
        return self._fresh

    def _near(self, box: Box, fresh: _Grid) -> list[int]:
        """The bodies whose boxes meet ``box``: Bullet's broadphase (its boxes are as the
        last step, a make or a put left them, a step's motion late at most: SLACK) and
        those placed since the last step (their links' boxes may be older)."""
        low, high = box
        hits = self.p.getOverlappingObjects([x - SLACK for x in low], [x + SLACK for x in high],
                                            physicsClientId=self.client) or ()
        found = dict.fromkeys(body for body, _ in hits)
        found.update(dict.fromkeys(fresh.near(box)))
        found.pop(self._ground, None)
        return list(found)

    def _clear_spot(self, body: int, box: Box, position: Vec3, orientation: Any, fresh: _Grid,
                    depth: float) -> Vec3 | None:
        """Put ``body`` at the nearest lattice spot around it where it is inside nothing;
        the offset (None: none within REACH, and it stays). Bodies of one size put at one
        spot share a search: the spots it passed are taken for the next one too."""
        sizes = tuple(round((high - low) * GAP, 9) for low, high in zip(*box))
        key = (tuple(round(x, 6) for x in box[0]), sizes)
        spots = self._searches.setdefault(key, _lattice(sizes))  # type: ignore[arg-type]
        self._searching.add(key)
        for offset in spots:
            shifted = _shifted(box, offset)
            if shifted[0][1] < -depth:
                continue  # under the ground
            crowded = [other for other in self._near(shifted, fresh) if other != body]
            self._put(body, _plus(position, offset), orientation)
            if not crowded or not self._inside(body, shifted, fresh, depth, near=crowded):
                return offset
        self._put(body, position, orientation)
        return None

    def _put(self, body: int, position: Vec3, orientation: Any) -> None:
        self.p.resetBasePositionAndOrientation(body, position, orientation,
                                               physicsClientId=self.client)

    def _inside(self, body: int, box: Box, fresh: _Grid, depth: float,
                skip: set[int] = frozenset(), ground: bool = True,  # type: ignore[assignment]
                near: list[int] | None = None) -> bool:
        """Is ``body`` (at ``box``) deeper than ``depth`` inside any body near (or the
        ground)?"""
        if ground and box[0][1] < -depth:
            return True
        for other in self._near(box, fresh) if near is None else near:
            if other != body and other not in skip and any(
                    point[8] < -depth for point in self.p.getClosestPoints(
                        body, other, 0.0, physicsClientId=self.client)):
                return True
        return False

    def _box(self, body: int) -> Box:
        """The world box around every link of ``body``."""
        get, client = self.p.getAABB, self.client
        boxes = [get(body, link, physicsClientId=client)
                 for link in range(-1, self.p.getNumJoints(body, physicsClientId=client))]
        return (tuple(min(b[0][k] for b in boxes) for k in range(3)),  # type: ignore[return-value]
                tuple(max(b[1][k] for b in boxes) for k in range(3)))


class _Grid:
    """Bodies by the cells of a uniform grid their boxes cover (a body larger than
    BIG cells is kept aside and always looked at)."""

    BIG = 512

    def __init__(self, cell: float) -> None:
        self.cell = cell
        self._cells: dict[tuple[int, int, int], list[int]] = {}
        self._boxes: dict[int, Box] = {}
        self._big: list[int] = []

    def _span(self, box: Box) -> list[range]:
        return [range(math.floor(low / self.cell), math.floor(high / self.cell) + 1)
                for low, high in zip(*box)]

    def add(self, body: int, box: Box) -> None:
        self._boxes[body] = box
        spans = self._span(box)
        if math.prod(len(span) for span in spans) > self.BIG:
            self._big.append(body)
            return
        for cell in product(*spans):
            self._cells.setdefault(cell, []).append(body)

    def remove(self, body: int) -> None:
        box = self._boxes.pop(body, None)
        if box is None:
            return
        if body in self._big:
            self._big.remove(body)
            return
        for cell in product(*self._span(box)):
            self._cells[cell].remove(body)

    def near(self, box: Box) -> list[int]:
        """The bodies whose boxes overlap ``box``."""
        found = dict.fromkeys(self._big)
        spans = self._span(box)
        if math.prod(len(span) for span in spans) <= self.BIG:
            for cell in product(*spans):
                found.update(dict.fromkeys(self._cells.get(cell, ())))
        else:
            found.update(dict.fromkeys(self._boxes))
        return [body for body in found if _overlap(self._boxes[body], box)]


def _overlap(a: Box, b: Box) -> bool:
    return all(a[0][k] < b[1][k] and b[0][k] < a[1][k] for k in range(3))


def _shifted(box: Box, offset: Vec3) -> Box:
    return _plus(box[0], offset), _plus(box[1], offset)


def _plus(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


@cache
def _steps() -> list[tuple[int, int, int]]:
    """Lattice steps within REACH, the nearest first (upward before downward), the
    spot itself left out."""
    return sorted((k for k in product(range(-REACH, REACH + 1), repeat=3) if any(k)),
                  key=lambda k: (k[0] ** 2 + k[1] ** 2 + k[2] ** 2, -k[1], k))


def _lattice(sizes: Vec3) -> Iterator[Vec3]:
    """Offsets of a lattice of ``sizes``, in the order of :func:`_steps`."""
    for i, j, k in _steps():
        yield (i * sizes[0], j * sizes[1], k * sizes[2])
