"""GLTF parts: parts shaped by mesh files (GLTFPart and the round and anthropomorphic hand parts).

The server reads the file (for rays and for the envelope); viewers load the same file
from its URL and draw it. A right palm or thumb is the left mesh mirrored in X.
"""

from __future__ import annotations

from typing import Any

from ..kit.errors import LimitExceeded
from ..kit.math3d import Vec3, euler_to_quat, rotate
from ..kit.numbers import Finite
from ..physics.assets import MeshFile
from ..physics.envelopes import Plane, envelope, half_space, pyramid
from . import part_figures
from .node import World
from .parts import Part

MAX_RECOLORS = 64  # recolor calls a part keeps (each is sent to every viewer that joins)

Color = Any  # a CSS colour name, "#hex", 0xRRGGBB or [r, g, b] in 0…1


class GLTFPart(Part):
    """Manual ``GLTFPart(filename, length=0)``: a mesh raised by length/2; no slots, no envelope.

    Files hold left-hand shapes: a part that is not ``left`` shows its file mirrored in X.
    """

    type_name = "GLTFPart"
    left = True

    def __init__(self, scene: World, node_id: str, filename: str, length: float = 0.0) -> None:
        self.mesh: MeshFile = scene.assets.mesh(filename)  # refused before the node exists
        super().__init__(scene, node_id)
        self.filename, self.length = filename, length
        self.recolors: tuple[tuple[Color, Color, float], ...] = ()
        self._envelope: Finite | None = None
        for figure in self.slot_figures():
            self.new_slot(*figure)
        if self.physical:
            self.envelope()  # made now: a shape it cannot be made for refuses the part

    def constructor_args(self) -> list[Any]:
        return [self.filename, self.length]

    @property
    def offset(self) -> Vec3:
        """Where the file's origin sits in the part's frame."""
        return (0.0, self.length / 2, 0.0)

    @property
    def mirror(self) -> bool:
        """True when the file is shown mirrored in X (a right-hand part)."""
        return not self.left

    def recolor(self, from_color: Color, to_color: Color, eps: float = 0.01) -> None:
        """Manual ``recolor(fromColor, toColor, eps)``: vertices within eps of one colour get another."""
        if len(self.recolors) >= MAX_RECOLORS:
            raise LimitExceeded(f"{self.id} has been recoloured {MAX_RECOLORS} times, the most "
                                f"a part keeps", limit="recolors", value=MAX_RECOLORS, object=self.id)
        self._assign("recolors", (*self.recolors, (from_color, to_color, eps)))

    def envelope(self) -> Finite:
        """Points whose convex hull is the part's collision envelope (part frame); made
        once, when a physical part is made (its shape never changes)."""
        if self._envelope is None:
            points = envelope(self.mesh, self.offset, self.mirror, self.envelope_cuts())
            self._envelope = Finite(Finite(p) for p in points)
        return self._envelope

    def envelope_cuts(self) -> list[Plane]:
        """Where the envelope stops short of the part's joints (nowhere unless a part says)."""
        return []

    def slot_figures(self) -> list[tuple[Any, ...]]:
        """Arguments of ``new_slot`` for each slot the part is made with (none here)."""
        return []

    def geometry(self) -> dict[str, Any]:
        shape: dict[str, Any] = {"kind": "mesh", "url": self.mesh.url,
                                 "offset": list(self.offset), "mirror": self.mirror}
        if self.physical:
            shape["points"] = self.envelope()
        return shape

    def properties(self) -> dict[str, Any]:
        return {**super().properties(), "recolors": [list(r) for r in self.recolors]}


class RoundFinger(GLTFPart):
    """Manual ``RoundFinger(filename, length=0.8)``: one slot at the top, (0, length, 0)."""

    type_name = "RoundFinger"
    physical = True

    def __init__(self, scene: World, node_id: str, filename: str,
                 length: float = part_figures.ROUND_FINGER_LENGTH) -> None:
        super().__init__(scene, node_id, filename, length)

    def slot_figures(self) -> list[tuple[Any, ...]]:
        return [((0.0, self.length, 0.0),)]

    def envelope_cuts(self) -> list[Plane]:
        gap, up, down = part_figures.FINGER_JOINT_GAP, (0.0, 1.0, 0.0), (0.0, -1.0, 0.0)
        return [*pyramid((0.0, 0.0, 0.0), up, gap), *pyramid((0.0, self.length, 0.0), down, gap)]


class HandedPart(GLTFPart):
    """A mesh part of a left or a right hand: ``(left, filename, length=1.4)``."""

    physical = True

    def __init__(self, scene: World, node_id: str, left: bool, filename: str,
                 length: float = part_figures.ROUND_PALM_LENGTH) -> None:
        self.left = left  # before the slots and the envelope, which depend on it
        super().__init__(scene, node_id, filename, length)

    def constructor_args(self) -> list[Any]:
        return [self.left, self.filename, self.length]


class RoundPalm(HandedPart):
    """Manual ``RoundPalm(left, filename, length=1.4)``: five finger slots, the thumb's first."""

    type_name = "RoundPalm"

    def envelope_cuts(self) -> list[Plane]:
        """Flat below each finger slot, and inside the thumb slot's side of the palm."""
        slots = self.slot_figures()
        gap = part_figures.PALM_JOINT_GAP
        cuts = [half_space(position, slot_direction(rotation, order), gap)
                for position, rotation, order in slots[1:]]
        return cuts + self.thumb_cuts(slots[0])

    def thumb_cuts(self, thumb: part_figures.SlotFigure) -> list[Plane]:
        side = 1.0 if self.left else -1.0
        return [half_space(thumb[0], (side, 0.0, 0.0), part_figures.PALM_JOINT_GAP)]

    def slot_figures(self) -> list[part_figures.SlotFigure]:
        return part_figures.round_palm_slots(self.left, self.length)


class AnthroPalm(RoundPalm):
    """Manual ``AnthroPalm(left, filename, length=1.4)``: the round palm cut for the thumb."""

    type_name = "AnthroPalm"

    def thumb_cuts(self, thumb: part_figures.SlotFigure) -> list[Plane]:
        return []  # the mesh is cut away where the thumb sits

    def slot_figures(self) -> list[part_figures.SlotFigure]:
        return part_figures.anthro_palm_slots(self.left, self.length)


class AnthroThumb(HandedPart):
    """Manual ``AnthroThumb(left, filename, length=1.4)``: not raised; one slot for its finger."""

    type_name = "AnthroThumb"

    def slot_figures(self) -> list[part_figures.SlotFigure]:
        return [part_figures.anthro_thumb_slot(self.left, self.length)]

    @property
    def offset(self) -> Vec3:
        return (0.0, 0.0, 0.0)

    def envelope_cuts(self) -> list[Plane]:
        """Clear of the palm while it swings about its motor's Z, and of its finger."""
        gap = part_figures.FINGER_JOINT_GAP
        [(position, rotation, order)] = self.slot_figures()
        toward_finger = slot_direction(rotation, order)
        return [*pyramid((0.0, 0.0, 0.0), (0.0, -1.0, 0.0), gap, ((1, 0, 0), (-1, 0, 0))),
                *pyramid(position, tuple(-c for c in toward_finger), gap)]


def slot_direction(rotation: Vec3, order: str) -> Vec3:
    """Where a part attached to a slot with this rotation points (the slot's +Y)."""
    return rotate(euler_to_quat(*rotation, order), (0.0, 1.0, 0.0))
