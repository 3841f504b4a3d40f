"""``box-and-blocks``: the Box and Blocks Test (Mathiowetz et al., 1985). A box of two
compartments split by a partition, 150 cubes of 2.5 cm in one; the score is how many
blocks the hand moves over the partition in 60 s (adults: 55-89), counted as the test's
examiner counts (:class:`Tally`): a block counts when it is carried over with the
fingertips across the partition, and blocks carried together count as one. The baseline
takes the highest block it can reach, carries it over and lets go, again and again."""

from __future__ import annotations

import random
from dataclasses import dataclass, field
from typing import Any, Callable

from ..objects import Box, Part
from ..robots import Robot
from ..session import Session
from . import progress
from .controller import Grip, prepare, smooth
from .grip import HandGrip
from .observation import rotate
from .scale import Scale
from .trial import TaskHand, drive, framed, under_hand

INSIDE = (0.537, 0.254)  # metres: the box inside, x (both compartments) by z
WALL_HEIGHT = 0.085
WALL = 0.01
PARTITION_HEIGHT = 0.152
BLOCK = 0.025
BLOCKS = 150
SECONDS = 60.0
BLOCK_MASS = 0.0105  # kilograms: a 2.5 cm pine cube
# the tripod grip of the grasp task: the block where thumb and fingers meet, the hand high
# enough that curling fingers clear what lies around it
GRIP = Grip(close=0.76, torque=0.3, side=0.015, gap=0.035)
# Contacts warm started (as the grasps', grasp.PHYSICS) at 30 solver iterations: 150 blocks
# at the grasps' 60 cost more than the heap needs. The edged hand's baseline (seeds 1-3)
# moved 18 blocks so against 14 at PyBullet's default 50 cold, in 88 % of the CPU
PHYSICS = {"solver_iterations": 30, "warm_start": 0.85}


@dataclass
class Stage:
    """The box in a scene, its blocks and the hand (made by the task: ``owned``); sizes
    in scene units."""

    session: Session
    scale: Scale
    hand: Robot
    grip: HandGrip
    blocks: list[Part]
    walls: list[Part]
    partition_x: float
    floor: float
    owned: bool = True

    def block_positions(self) -> list[list[float]]:
        return framed(self.session, lambda mirror: [list(mirror.nodes[b.id]["position"])
                                                    for b in self.blocks if b.id in mirror.nodes])

    def past(self, x: float) -> bool:
        """Whether a place ``x`` along the box is past the partition (every block starts
        on its -x side)."""
        return x > self.partition_x

    def moved(self) -> int:
        """Blocks past the partition and down in its compartment (not held over the wall)."""
        top = self.floor + self.scale.length(WALL_HEIGHT)
        return sum(self.past(p[0]) and p[1] < top for p in self.block_positions())

    def across(self) -> tuple[set[str], bool]:
        """The blocks past the partition now, and whether every fingertip is (where each
        digit's tip is open, carried with the hand's pose: closing curls a tip under the
        palm, not across the box)."""
        def read(mirror: Any) -> tuple[set[str], bool]:
            blocks = {b.id for b in self.blocks
                      if b.id in mirror.nodes and self.past(mirror.nodes[b.id]["position"][0])}
            hand = mirror.nodes.get(self.hand.id)
            tips = [d.at for d in self.grip.digits if d.at is not None]
            if hand is None or not tips:
                return blocks, False
            return blocks, all(self.past(hand["position"][0] + rotate(hand["quaternion"], tip)[0])
                               for tip in tips)
        return framed(self.session, read)

    def remove(self) -> None:
        for node in ((self.hand,) if self.owned else ()) + (*self.blocks, *self.walls):
            node.delete()


def _wall(session: Session, size: tuple[float, float, float], at: tuple[float, float, float]) -> Part:
    wall = Box(*size, "peru", scene=session)
    wall.set_position(*at)
    wall.set_static(True)
    return wall


def build(session: Session, hands: TaskHand, rng: random.Random, count: int = BLOCKS) -> Stage:
    """The box (floor, walls, partition) at the origin, ``count`` blocks heaped in the -x
    compartment, the hand over it."""
    scale = Scale.of(session)
    sx, sz = (scale.length(v) for v in INSIDE)
    wall, height, block = scale.length(WALL), scale.length(WALL_HEIGHT), scale.length(BLOCK)
    with session.connection.gathering():
        walls = [_wall(session, (sx + 2 * wall, wall, sz + 2 * wall), (0, wall / 2, 0)),
                 _wall(session, (wall, scale.length(PARTITION_HEIGHT), sz), (0, wall + scale.length(PARTITION_HEIGHT) / 2, 0))]
        for side in (-1, 1):
            walls.append(_wall(session, (wall, height, sz + 2 * wall), (side * (sx + wall) / 2, wall + height / 2, 0)))
            walls.append(_wall(session, (sx + 2 * wall, height, wall), (0, wall + height / 2, side * (sz + wall) / 2)))
    per_row = int((sx / 2 - block) // (block * 1.15))
    per_column = int((sz - block) // (block * 1.15))
    blocks = []
    for index in range(count):
        layer, cell = divmod(index, per_row * per_column)
        row, column = divmod(cell, per_column)
        at = (-sx / 2 + block * (0.8 + 1.15 * row), wall + block * (0.55 + 1.1 * layer),
              -sz / 2 + block * (0.8 + 1.15 * column))
        with session.connection.gathering():
            cube = Box(block, block, block, rng.choice(("crimson", "royalblue", "gold", "seagreen")),
                       scene=session)
            cube.set_position(*at)
            cube.set_rotation(0, rng.uniform(-0.2, 0.2), 0)
            cube.set_mass(BLOCK_MASS)
        blocks.append(cube)
    hand, grip = hands.make(session)
    hand.set_position(-sx / 4, wall + scale.length(PARTITION_HEIGHT) * 1.6 + grip.layout.palm_below,
                      -under_hand(grip.layout, scale, GRIP)[1])
    session.sync()
    prepare(hand, GRIP)
    return Stage(session, scale, hand, grip, blocks, walls, 0.0, wall, hands.source.owned)


@dataclass
class Tally:
    """The examiner's count (Mathiowetz et al., 1985): a block that goes over the partition
    counts once the fingertips are across it too (thrown or pushed over, it does not);
    blocks that go over in one carry (from the tips' crossing until they come back) count
    as one. ``across``: every block that went over, however."""

    blocks: int = 0
    across: int = 0
    seen: set[str] = field(default_factory=set)
    waiting: bool = False    # a block went over, the fingertips not yet
    credited: bool = False   # this carry has counted its block

    def step(self, stage: Stage) -> None:
        """Look at the box once (a tick)."""
        over, tips_across = stage.across()
        new = over - self.seen
        self.seen |= over
        self.across += len(new)
        if new and not (tips_across and self.credited):
            self.waiting = True
        if tips_across and self.waiting:
            self.blocks += 1
            self.waiting, self.credited = False, True
        if not tips_across:
            self.credited = False


CYCLE = (("reach", 0.5), ("descend", 0.5), ("close", 0.7), ("lift", 0.5), ("carry", 0.6),
         ("open", 0.3), ("back", 0.4))


class Baseline:
    """Over the highest block on the start side, down onto it, close, up over the
    partition, across, open; then again."""

    def __init__(self, stage: Stage) -> None:
        self.stage = stage
        layout = stage.grip.layout
        self.grasp_at = under_hand(layout, stage.scale, GRIP)  # where the block lies from the hand
        self.high = stage.floor + stage.scale.length(PARTITION_HEIGHT) * 1.5 + layout.palm_below
        self.cycle_start = 0.0
        self.target: list[float] | None = None

    def _pick(self) -> list[float] | None:
        left = [p for p in self.stage.block_positions() if p[0] < -self.stage.scale.length(BLOCK)]
        return max(left, key=lambda p: p[1]) if left else None

    def __call__(self, t: float) -> None:
        hand, scale = self.stage.hand, self.stage.scale
        phase_t = t - self.cycle_start
        if phase_t >= sum(span for _, span in CYCLE) or self.target is None:
            self.cycle_start, phase_t = t, 0.0
            self.target = self._pick()
            if self.target is None:
                return
        name, into = _phase(phase_t)
        bx, by, bz = self.target
        hx, hz = bx - self.grasp_at[0], bz - self.grasp_at[1]
        layout, block = self.stage.grip.layout, scale.length(BLOCK)
        # the palm just over the block; higher when the digits hang further (a gripper)
        down = by - block / 2 + scale.length(GRIP.gap) + max(block + layout.palm_below, layout.lowest)
        across = -hx  # as far past the partition as the block was before it
        ease = smooth(into, 0.0, 1.0)
        x, y = {"reach": (hx, self.high), "descend": (hx, self.high + (down - self.high) * ease),
                "close": (hx, down), "lift": (hx, down + (self.high - down) * ease),
                "carry": (hx + (across - hx) * ease, self.high), "open": (across, self.high),
                "back": (across, self.high)}[name]
        hand.set_position(x, y, hz)
        # the opposing digit closes first, behind the block, then the others push it against it
        thumb = {"close": smooth(into, 0.0, 0.7), "lift": 1.0, "carry": 1.0, "open": 1 - into}
        fingers = {"close": smooth(into, 0.3, 0.7), "lift": 1.0, "carry": 1.0, "open": 1 - into}
        grip = self.stage.grip
        hand.set_angles(*grip.angles({
            index: GRIP.close * (thumb if index == grip.opposing else fingers).get(name, 0.0)
            for index in range(len(grip.digits))}))


def _phase(t: float) -> tuple[str, float]:
    for name, span in CYCLE:
        if t < span:
            return name, t / span
        t -= span
    return CYCLE[-1][0], 1.0


def box_and_blocks(session: Session, hands: TaskHand, seed: int, *,
                   controller: Callable[[Stage], Callable[[float], None]] = Baseline,
                   seconds: float = SECONDS, blocks: int = BLOCKS) -> dict[str, Any]:
    """The test once: the blocks moved in ``seconds`` (the test's 60) of scene time, as
    the examiner counts them (``blocks``) and as they lie (``blocksOver``: past the
    partition at the end, however they got there)."""
    # paused first: a scene another run steps is refused before anything of it changes
    with session.paused():  # stepped tick by tick (drive): the same run on any load
        session.set_physics("dynamic", **PHYSICS)
        session.sync()
        with progress.shown(seconds + 2.0, f"box-and-blocks {hands.source.name}"):
            stage = build(session, hands, random.Random(seed), blocks)
            tally, moved = run(stage, controller(stage), seconds)
        return {"task": "box-and-blocks", "hand": hands.source.name, "seed": seed, "seconds": seconds,
                "scale": stage.scale.factor, "unit": stage.scale.unit, "blocks": tally.blocks,
                "blocksOver": moved, "blocksAcross": tally.across, "humanNorm": [55, 89]}


def run(stage: Stage, hand: Callable[[float], None], seconds: float) -> tuple[Tally, int]:
    """The heap settled, ``hand`` driven for ``seconds``, what it let go landed; the
    examiner's tally and the blocks past the partition that were not before. The box
    is cleared away."""
    session = stage.session
    drive(session, 1.0, lambda t: None)
    before = stage.moved()
    tally = Tally(seen=stage.across()[0])

    def step(t: float) -> None:
        counted(t)  # what the last tick left, before this one's orders
        hand(t)

    def counted(t: float) -> None:
        tally.step(stage)
        progress.tell(f"blocks moved: {tally.blocks}")
    drive(session, seconds, step)
    drive(session, 1.0, counted)
    moved = stage.moved() - before
    stage.remove()
    return tally, moved
