"""A trial: one hand, its table and its object, side by side with the others of its batch;
and the loop that drives a batch tick by tick."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Protocol, Sequence, TypeVar

from ..mirror import Mirror
from ..objects import Box, Part
from ..robots import Robot
from ..sensor import Sensor
from ..session import Session
from .grip import HandGrip, Layout, hand_grip
from .hands import HandSource
from . import progress
from .objects import TestObject
from .scale import Scale

TABLE_TOP = 0.4  # × the hand's length: the tables' height
SPACING = 2.2    # × the hand's length: from one trial's hand to the next
# how a cylinder is laid: a quarter turn about z, on its side (x, y, z, w)
LYING = (0.0, 0.0, math.sin(math.pi / 4), math.cos(math.pi / 4))

T = TypeVar("T")


class Placement(Protocol):
    """Where an object lies under the hand: at the hand's grasp point (where its tips meet
    half closed), ``reach`` hand lengths further ahead, ``side`` metres (human) towards
    the opposing digit, ``gap`` metres (human) below the palm."""

    reach: float
    side: float
    gap: float


@dataclass
class TaskHand:
    """Where a task's hands come from and how they grip: the grip is read from the first
    hand made (every hand of a source is built alike) with the file's override, if any."""

    source: HandSource
    override: dict[str, Any] | None = None
    grip: HandGrip | None = None

    def make(self, session: Session) -> tuple[Robot, HandGrip]:
        """A hand, turned palm down where it was made, its digits open and preshaped."""
        robot = self.source.make(session)
        if self.grip is None:
            self.grip = hand_grip(robot, self.override)
        with session.connection.gathering():
            robot.set_quaternion(list(self.grip.layout.quaternion))
            robot.set_angles(*self.grip.angles({i: 0.0 for i in range(len(self.grip.digits))}))
        return robot, self.grip


@dataclass
class Trial:
    """One hand over one object on one table. ``home`` is the hand's position with the
    object under its grasp; ``lift`` how far a controller lifts it (both scene units)."""

    session: Session
    scale: Scale
    hand: Robot
    grip: HandGrip
    obj: Part
    table: Part
    item: TestObject
    home: tuple[float, float, float]
    table_top: float
    mass: float       # kilograms (human)
    friction: float
    lift: float
    owned: bool = True  # the task made the hand (and removes it with the trial)
    sensor: Sensor | None = None  # on the object, watched: who presses it how, each frame
    heights: list[float] = field(default_factory=list)
    offsets: list[tuple[float, ...]] = field(default_factory=list)
    forces: list[float] = field(default_factory=list)
    touched: list[tuple[float, ...]] = field(default_factory=list)  # offsets since first contact
    poses: list[tuple[list[float], list[float]]] = field(default_factory=list)  # the object's, observed
    start: tuple[float, ...] = (0.0, 0.0, 0.0)  # where the object was laid (scene units)
    start_quaternion: tuple[float, ...] = (0.0, 0.0, 0.0, 1.0)  # and how it was turned
    # the motor targets and the wrist's place last sent (not copied by dataclasses.replace:
    # a new episode's own)
    targets: tuple[float | None, ...] = field(default=(), init=False, compare=False)
    wrist: tuple[float, ...] = field(default=(), init=False, compare=False)

    @property
    def layout(self) -> Layout:
        return self.grip.layout

    def set_motors(self, *angles: float | None) -> None:
        """The hand's motor targets (``set_angles``), sent only when they changed: the same
        targets again change nothing, yet cost the server a request's work each tick (the
        baseline keeps its targets for four fifths of a grasp)."""
        if angles != self.targets:
            self.targets = angles
            self.hand.set_angles(*angles)

    def set_wrist(self, x: float, y: float, z: float) -> None:
        """The hand's place (``set_position``), sent only when it changed: its mount holds it
        where it was put (the server holds a hand put where it is exactly as one left
        there), yet each place sent costs the server a request and a glide (the baseline
        holds the wrist still for three quarters of a grasp)."""
        if (x, y, z) != self.wrist:
            self.wrist = (x, y, z)
            self.hand.set_position(x, y, z)

    def _node(self, node_id: str, key: str) -> list[float]:
        return framed(self.session, lambda mirror: list(mirror.nodes[node_id][key]))

    def object_position(self) -> list[float]:
        return self._node(self.obj.id, "position")

    def hand_position(self) -> list[float]:
        return self._node(self.hand.id, "position")

    def object_quaternion(self) -> list[float]:
        return self._node(self.obj.id, "quaternion")

    def hand_quaternion(self) -> list[float]:
        return self._node(self.hand.id, "quaternion")

    def object_offset(self) -> list[float]:
        """From the hand's position to the object's (scene units)."""
        return [a - b for a, b in zip(self.object_position(), self.hand_position())]

    def object_contacts(self) -> list[dict[str, Any]]:
        """What presses on the object at the last frame, body by body (ids, newtons)."""
        if self.sensor is None:
            return []
        return [{**c, "other": getattr(c["other"], "id", c["other"])} for c in self.sensor.sense_contacts()]

    def observe(self) -> None:
        """Note the object's height above the table, where it is relative to the hand
        and the force on it (human newtons)."""
        position = self.object_position()
        bottom = position[1] - self.scale.length(self.item.size[1]) / 2
        self.heights.append(bottom - self.table_top)
        self.offsets.append(tuple(self.object_offset()))
        self.poses.append((position, self.object_quaternion()))
        force = framed(self.session, lambda mirror: mirror.forces.get(self.obj.id, 0.0))
        self.forces.append(force)

    def watch_contact(self) -> None:
        """Once the hand first touches the object, note where the object is relative to
        the hand every step (what :meth:`slip_from_contact` measures)."""
        if not self.touched and not any(c["other"] not in (self.table.id, "ground")
                                        for c in self.object_contacts()):
            return
        self.touched.append(tuple(self.object_offset()))

    def slip(self) -> float:
        """How far the object moved in the hand while observed (human metres)."""
        return self._moved(self.offsets)

    def slip_from_contact(self) -> float:
        """How far the object moved in the hand from its first contact with the hand to
        the end (human metres): what closing and lifting dragged it too."""
        return self._moved(self.touched)

    def _moved(self, offsets: list[tuple[float, ...]]) -> float:
        if not offsets:
            return 0.0
        return self.scale.metres(max(math.dist(offsets[0], o) for o in offsets))

    def remove(self) -> None:
        for node in (self.hand, self.obj, self.table) if self.owned else (self.obj, self.table):
            node.delete()


def under_hand(layout: Layout, scale: Scale, place: Placement) -> tuple[float, float]:
    """Where an object placed by ``place`` lies relative to the hand's position, palm
    down: its (x, z) offset in scene units."""
    return (layout.grasp[0] + layout.thumb_side * scale.length(place.side),
            layout.grasp[2] - place.reach * layout.length)


def lay_out(session: Session, hands: TaskHand, item: TestObject, draws: Sequence[tuple[float, float]],
            weight: float, place: Placement) -> list[Trial]:
    """A row of trials, one per ``(mass factor, friction factor)`` draw: each hand palm
    down and open ``lift`` above its object, the object where ``place`` says."""
    scale = Scale.of(session)
    trials = []
    for index, (mass_factor, friction_factor) in enumerate(draws):
        hand, grip = hands.make(session)
        length = grip.layout.length
        top = TABLE_TOP * length
        size = [scale.length(v) for v in item.size]
        dx, dz = under_hand(grip.layout, scale, place)
        x = index * SPACING * length
        at = (x + dx, top + size[1] / 2, dz)
        gap = scale.length(place.gap)
        # the palm just over the object; higher when the digits hang further (a gripper)
        home = (x, top + gap + max(size[1] + grip.layout.palm_below, grip.layout.lowest), 0.0)
        # placed in the message that turned it: in dynamic mode a robot placed a tick
        # after it was made would be dragged there from where it was made (the task
        # holds the scene paused, so no tick comes between)
        with session.connection.gathering():
            hand.set_position(home[0], home[1] + 0.6 * length, home[2])
            table = Box(1.6 * length, top, 1.6 * length, "burlywood", scene=session)
            table.set_position(at[0], top / 2, at[2])
            table.set_static(True)
            obj = item.make(session, scale)
            obj.set_position(*at)
            if item.shape == "cylinder":
                obj.set_quaternion(list(LYING))
            obj.set_mass(weight * mass_factor)
            obj.set_friction(friction_factor)
        # an invisible sensor on the object (it has no body: the object's physics stays
        # as it was), watched: frames tell which digit presses it how hard
        sensor = Sensor(False, scene=session).attach_to_slot(obj, obj.add_slot(0, 0, 0))
        sensor.watch()
        turned = LYING if item.shape == "cylinder" else (0.0, 0.0, 0.0, 1.0)
        trials.append(Trial(session, scale, hand, grip, obj, table, item, home, top,
                            weight * mass_factor, friction_factor, 0.6 * length, hands.source.owned,
                            sensor, start=at, start_quaternion=turned))
    return trials


def framed(session: Session, reader: Callable[[Mirror], T]) -> T:
    """``reader`` on the mirror as the last frame left it, without waiting for answers
    (:meth:`Session.read` waits): inside :func:`drive` every tick ends answered, so a
    step's reads see the moment the step began, whatever it has sent since, and none
    costs a round trip (a read that waited sent what the step had gathered and waited
    for its answer: two messages a tick instead of one)."""
    with session.lock:
        return reader(session.mirror)


def drive(session: Session, seconds: float, step: Callable[[float], Any]) -> None:
    """Call ``step(t)`` once a tick, ``t`` the scene seconds since the start, until
    ``seconds`` have passed; what a step sends leaves with the tick as one message, then
    the scene, paused (:meth:`Session.paused`; a task holds it paused from start to end),
    takes one tick. A controller driven so sees the same world however loaded the server
    is, and a trial runs as fast as the server computes it. A step reads the last frame
    with :func:`framed`."""
    period = 1.0 / session.tick_rate
    last = round(seconds / period)
    with session.paused():
        for tick in range(last + 1):
            with session.connection.gathering():
                step(tick * period)
                if tick % progress.CAPTION_TICKS == 0 or tick == last:
                    progress.caption_to(session)
                session.step()  # with the step's setters: one message, one answer a tick
            progress.advance(period)
