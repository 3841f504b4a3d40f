"""Robotic hands: fixed chains of hand parts with finger-level control."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Callable

from ..errors import OutOfRange
from . import figures
from .motor import Motor, MotorX, MotorZ
from .node import Node
from .parts import EdgedFinger, EdgedPalm, EdgedTip
from .robot import Robot

if TYPE_CHECKING:
    from .scene import Scene

FINGERS = 5


class Hand(Robot):
    """A robot with five fingers (thumb first) and finger-level motor groups.

    Subclasses say which motor indices spread and flex each finger; the parts inside
    get ids ``<hand>/<k>`` so that every client can address them. The motors are those
    the hand was built with: a motor deleted or moved to another robot is skipped, so a
    hand method never turns a motor of another finger (or of another robot).
    """

    spread_thumb: Callable[[float], float] = staticmethod(lambda a: a)

    def __init__(self, scene: Scene, node_id: str, is_left: bool = True) -> None:
        super().__init__(scene, node_id)
        self.is_left = is_left
        self._parts_made = 0
        self._built: list[Motor] = []

    def make(self, cls: type[Node], *args: Any) -> Any:
        """A new part of this hand with the next inner id."""
        node = cls(self.scene, f"{self.id}/{self._parts_made}", *args)
        self._parts_made += 1
        return node

    def spread_index(self, finger: int) -> int:
        """Index of the motor that spreads ``finger``."""
        return 4 * finger

    def flex_indices(self, finger: int) -> range:
        """Indices of the motors that flex ``finger``."""
        return range(4 * finger + 1, 4 * finger + 4)

    def built(self) -> None:
        """Subclasses call this once their parts are in place: these are the hand's motors."""
        self._built = list(self.get_motors())

    def _motor(self, index: int) -> Motor | None:
        motor = self._built[index]
        return motor if motor.id in self.scene.nodes and motor.root() is self else None

    @staticmethod
    def _check_finger(index: int) -> None:
        if not 0 <= index < FINGERS:
            raise OutOfRange(f"finger index {index} is not 0…4 (thumb, index, middle, "
                             f"ring, little)", finger=index)

    def flex_finger(self, index: int, angle: float | None) -> None:
        """Manual ``flexFinger(index, angle)``: every flexing motor of the finger to -angle."""
        self._check_finger(index)
        for i in self.flex_indices(index):
            self._turn(i, angle)

    def flex_fingers(self, angle: float | None) -> None:
        """Manual ``flexFingers(angle)``."""
        for finger in range(FINGERS):
            self.flex_finger(finger, angle)

    def spread_finger(self, index: int, angle: float | None) -> None:
        """Manual ``spreadFinger(index, angle)``: the finger's base motor to -angle."""
        self._check_finger(index)
        self._turn(self.spread_index(index), angle)

    def _turn(self, index: int, angle: float | None) -> None:
        """Motor ``index`` of the hand to -angle, if the hand still has it."""
        motor = self._motor(index)
        if motor is not None:
            motor.set_angle(None if angle is None else -angle)

    def spread_fingers(self, angle: float, include_thumb: bool = False) -> None:
        """Manual ``spreadFingers(angle, includeThumb=false)``."""
        if include_thumb:
            self.spread_finger(0, self.spread_thumb(angle))
        for finger, share in enumerate(figures.SPREAD_FINGERS, start=1):
            self.spread_finger(finger, share * angle)


class EdgedHand(Hand):
    """Manual ``EdgedHand(isLeft)``: an edged palm with five three-segment fingers."""

    type_name = "EdgedHand"
    spread_thumb = staticmethod(figures.SPREAD_THUMB["EdgedHand"])

    def __init__(self, scene: Scene, node_id: str, is_left: bool = True) -> None:
        super().__init__(scene, node_id, is_left)
        self.palm = self.make(EdgedPalm, is_left)
        self.palm.attach_to_slot(self)
        for finger in range(FINGERS):
            spread = self.make(MotorX, *figures.edged_spread_motor(finger)).flip(is_left)
            spread.attach_to_slot(self.palm, finger)
            self.add_chain(
                spread,
                self.make(MotorZ, *figures.EDGED_FLEX_MOTOR),
                self.make(EdgedFinger, figures.EDGED_FINGER_SIZES[finger]),
                self.make(MotorZ, *figures.EDGED_FLEX_MOTOR),
                self.make(EdgedFinger, 0.5),
                self.make(MotorZ, *figures.EDGED_FLEX_MOTOR),
                self.make(EdgedTip, 0.5),
            )
        self.built()
