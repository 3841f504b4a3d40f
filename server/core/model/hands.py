"""Robotic hands: fixed chains of hand parts with finger-level control."""

from __future__ import annotations

from functools import cache
from typing import Any

from ..kit.errors import OutOfRange
from . import part_figures
from .gltf_parts import AnthroPalm, AnthroThumb, GLTFPart, RoundFinger, RoundPalm
from .motor import Motor, MotorX, MotorY, MotorZ
from .node import Node, World
from .parts import EdgedFinger, EdgedPalm, EdgedTip
from .robot import Robot

FINGERS = 5


class Hand(Robot):
    """A robot with five fingers (thumb first) and finger-level motor groups.

    Subclasses say which motor indices spread and flex each finger; the parts inside
    get ids ``<hand>/<k>`` so that every client can address them. The motors are those
    the hand was built with: a motor deleted or moved to another robot is skipped, so a
    hand method never turns a motor of another finger (or of another robot).
    """

    thumb_spread: tuple[float, float] = (0.0, 1.0)  # the thumb's spread: offset + scale * angle

    def __init__(self, scene: World, node_id: str, is_left: bool = True) -> None:
        super().__init__(scene, node_id)
        self.is_left = is_left
        self._parts_made = 0
        self._built: list[Motor] = []
        self._present: tuple[int, list[Motor | None]] | None = None  # (tree version, motors)

    def constructor_args(self) -> list[Any]:
        return [self.is_left]

    def make(self, cls: type[Node], *args: Any) -> Any:
        """A new part of this hand with the next inner id."""
        node = cls(self.scene, f"{self.id}/{self._parts_made}", *args)
        self._parts_made += 1
        return node

    @classmethod
    def spread_index(cls, finger: int) -> int:
        """Index of the motor that spreads ``finger``."""
        return 4 * finger

    @classmethod
    def flex_indices(cls, finger: int) -> range:
        """Indices of the motors that flex ``finger``."""
        return range(4 * finger + 1, 4 * finger + 4)

    def built(self) -> None:
        """Subclasses call this once their parts are in place: these are the hand's motors."""
        self._built = list(self.get_motors())

    def _motors_present(self) -> list[Motor | None]:
        """The hand's motors by index, None for one deleted or detached (looked up again
        only when the scene's tree changed: every move of a node changes it)."""
        version = self.scene.tree_version
        if self._present is None or self._present[0] != version:
            nodes = self.scene.nodes
            self._present = (version, [motor if motor.id in nodes and motor.root() is self
                                       else None for motor in self._built])
        return self._present[1]

    @staticmethod
    def _check_finger(index: int) -> None:
        if not 0 <= index < FINGERS:
            raise OutOfRange(f"finger index {index} is not 0…4 (thumb, index, middle, "
                             f"ring, little)", finger=index)

    def flex_finger(self, index: int, angle: float | None) -> None:
        """Manual ``flexFinger(index, angle)``: every flexing motor of the finger to -angle."""
        self._check_finger(index)
        self._turn([(i, angle) for i in self.flex_indices(index)])

    def flex_fingers(self, angle: float | None) -> None:
        """Manual ``flexFingers(angle)``."""
        self._turn([(i, angle) for i in self.every_flex_index()])

    @classmethod
    @cache
    def every_flex_index(cls) -> tuple[int, ...]:
        """The flexing motors' indices of every finger, thumb first."""
        return tuple(i for finger in range(FINGERS) for i in cls.flex_indices(finger))

    def spread_finger(self, index: int, angle: float | None) -> None:
        """Manual ``spreadFinger(index, angle)``: the finger's base motor to -angle."""
        self._check_finger(index)
        self._turn([(self.spread_index(index), angle)])

    def spread_fingers(self, angle: float, include_thumb: bool = False) -> None:
        """Manual ``spreadFingers(angle, includeThumb=false)``."""
        offset, scale = self.thumb_spread
        turns = [(self.spread_index(0), offset + scale * angle)] if include_thumb else []
        turns += [(self.spread_index(finger), share * angle)
                  for finger, share in enumerate(part_figures.SPREAD_FINGERS, start=1)]
        self._turn(turns)

    def _turn(self, turns: list[tuple[int, float | None]]) -> None:
        """Motors (by index) to -angle, those the hand still has, in one pass."""
        present = self._motors_present()
        self.scene.turn([(motor, None if angle is None else -angle)
                         for index, angle in turns if (motor := present[index]) is not None])


class EdgedHand(Hand):
    """Manual ``EdgedHand(isLeft)``: an edged palm with five three-segment fingers."""

    type_name = "EdgedHand"
    thumb_spread = part_figures.SPREAD_THUMB["EdgedHand"]

    def __init__(self, scene: World, node_id: str, is_left: bool = True) -> None:
        super().__init__(scene, node_id, is_left)
        self.palm = self.make(EdgedPalm, is_left)
        self.palm.attach_to_slot(self)
        for finger in range(FINGERS):
            spread = self.make(MotorX, *part_figures.edged_spread_motor(finger)).flip(is_left)
            spread.attach_to_slot(self.palm, finger)
            self.add_chain(
                spread,
                self.make(MotorZ, *part_figures.EDGED_FLEX_MOTOR),
                self.make(EdgedFinger, part_figures.EDGED_FINGER_SIZES[finger]),
                self.make(MotorZ, *part_figures.EDGED_FLEX_MOTOR),
                self.make(EdgedFinger, 0.5),
                self.make(MotorZ, *part_figures.EDGED_FLEX_MOTOR),
                self.make(EdgedTip, 0.5),
            )
        self.built()


MOTOR_TYPES: dict[str, type[Motor]] = {"MotorX": MotorX, "MotorY": MotorY, "MotorZ": MotorZ}


class RoundHand(Hand):
    """Manual ``RoundHand(isLeft)``: a round palm with five three-segment round fingers."""

    type_name = "RoundHand"
    thumb_spread = part_figures.SPREAD_THUMB["RoundHand"]
    palm_type: type[RoundPalm] = RoundPalm
    palm_file = "round-palm.glb"

    def __init__(self, scene: World, node_id: str, is_left: bool = True) -> None:
        super().__init__(scene, node_id, is_left)
        self.palm = self.round(self.make(self.palm_type, is_left, self.palm_file))
        self.palm.attach_to_slot(self)
        self.build_fingers()
        self.built()

    def round(self, part: GLTFPart) -> GLTFPart:
        """A part of this hand, its blue recoloured grey as 1.0's round hands do."""
        part.recolor(list(part_figures.MESH_BLUE), list(part_figures.ROUND_HAND_GREY))
        return part

    def motor(self, motor_type: str, name: str, arguments: tuple[float, ...],
              flip_when_left: bool | None) -> Motor:
        """A named motor of this hand, flipped on the side the figures say."""
        motor = self.make(MOTOR_TYPES[motor_type], *arguments).set_name(name)
        if flip_when_left is not None:
            motor.flip(self.is_left if flip_when_left else not self.is_left)
        return motor

    def flexing(self, base: Node, flex: list[tuple[str, tuple[float, ...]]]) -> None:
        """Flexing motors and round fingers, in turn, from ``base`` on."""
        chain: list[Node] = [base]
        for (name, arguments), (file, length) in zip(flex, _ROUND_SEGMENTS):
            chain += [self.motor("MotorZ", name, arguments, None),
                      self.round(self.make(RoundFinger, file, length))]
        self.add_chain(*chain)

    def finger(self, finger: int, spread: tuple[Any, ...],
               flex: list[tuple[str, tuple[float, ...]]]) -> None:
        """A finger on its palm slot: the named spread motor, then ``flexing``."""
        kind, *arguments, flip_when_left = spread
        motor = self.motor(kind, part_figures.FINGER_NAMES[finger], tuple(arguments), flip_when_left)
        motor.attach_to_slot(self.palm, finger)
        self.flexing(motor, flex)

    def build_fingers(self) -> None:
        for finger in range(FINGERS):
            self.finger(finger, part_figures.ROUND_THUMB_SPREAD if finger == 0
                        else part_figures.ROUND_FINGER_SPREAD, _ROUND_MOTORS)


_ROUND_SEGMENTS = [(file, length) for _, _, file, length in part_figures.ROUND_FLEX]
_ROUND_MOTORS = [(name, arguments) for name, arguments, _, _ in part_figures.ROUND_FLEX]
_ANTHRO_MOTORS = [("proximal", part_figures.ANTHRO_PROXIMAL), ("middle", part_figures.ANTHRO_FLEX),
                  ("distal", part_figures.ANTHRO_FLEX)]


class AnthroHand(RoundHand):
    """Manual ``AnthroHand(isLeft)``: an anthropomorphic palm and thumb, round fingers."""

    type_name = "AnthroHand"
    thumb_spread = part_figures.SPREAD_THUMB["AnthroHand"]
    palm_type = AnthroPalm
    palm_file = "anthro-palm.glb"

    @classmethod
    def spread_index(cls, finger: int) -> int:
        return 1 if finger == 0 else 4 * finger + 2

    @classmethod
    def flex_indices(cls, finger: int) -> range:
        return range(4 * finger + 3, 4 * finger + 6)

    def build_fingers(self) -> None:
        (palm_type, palm_name, *palm_args, palm_flip), *thumb_motors = part_figures.ANTHRO_THUMB_MOTORS
        base = self.motor(palm_type, palm_name, tuple(palm_args), palm_flip)
        base.attach_to_slot(self.palm, 0)
        chain: list[Node] = [base, self.round(self.make(AnthroThumb, self.is_left, "anthro-thumb.glb"))]
        for motor_type, name, *arguments, flip_when_left in thumb_motors[:-1]:
            chain.append(self.motor(motor_type, name, tuple(arguments), flip_when_left))
        self.add_chain(*chain)
        _, proximal_name, *proximal, _ = thumb_motors[-1]
        self.flexing(chain[-1], [(proximal_name, tuple(proximal)), *_ANTHRO_MOTORS[1:]])
        for finger in range(1, FINGERS):
            self.finger(finger, part_figures.ROUND_FINGER_SPREAD, _ANTHRO_MOTORS)
