"""Parts shaped by mesh files: GLTFPart and the round and anthropomorphic hand parts.

The server reads the file (for rays and for the envelope); viewers load the same file
from its URL and draw it. A right palm or thumb is the left mesh mirrored in X.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..errors import LimitExceeded
from . import figures
from .assets import EVERYWHERE, Box, Mesh, envelope
from .math3d import Vec3
from .parts import Part

if TYPE_CHECKING:
    from .scene import Scene

MAX_RECOLORS = 64  # recolor calls a part keeps (each is sent to every viewer that joins)

Color = Any  # a CSS colour name, "#hex", 0xRRGGBB or [r, g, b] in 0…1


class GLTFPart(Part):
    """Manual ``GLTFPart(filename, length=0)``: a mesh raised by length/2; no slots, no envelope.

    Files hold left-hand shapes: a part that is not ``left`` shows its file mirrored in X.
    """

    type_name = "GLTFPart"
    left = True

    def __init__(self, scene: Scene, node_id: str, filename: str, length: float = 0.0) -> None:
        self.mesh: Mesh = scene.assets.mesh(filename)  # refused before the node exists
        super().__init__(scene, node_id)
        self.filename, self.length = filename, length
        self.recolors: tuple[tuple[Color, Color, float], ...] = ()

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

    def envelope(self) -> tuple[Vec3, ...]:
        """Points whose convex hull is the part's collision envelope (part frame)."""
        return envelope(self.mesh, self.offset, self.mirror, self.envelope_box())

    def envelope_box(self) -> Box:
        """Where the envelope may reach (the whole mesh unless a part says otherwise)."""
        return EVERYWHERE

    def geometry(self) -> dict[str, Any]:
        shape: dict[str, Any] = {"kind": "mesh", "url": self.mesh.url,
                                 "offset": list(self.offset), "mirror": self.mirror}
        if self.physical:
            shape["points"] = [list(p) for p in self.envelope()]
        return shape

    def properties(self) -> dict[str, Any]:
        return {**super().properties(), "recolors": [list(r) for r in self.recolors]}


class RoundFinger(GLTFPart):
    """Manual ``RoundFinger(filename, length=0.8)``: one slot at the top, (0, length, 0)."""

    type_name = "RoundFinger"
    physical = True

    def __init__(self, scene: Scene, node_id: str, filename: str,
                 length: float = figures.ROUND_FINGER_LENGTH) -> None:
        super().__init__(scene, node_id, filename, length)
        self.new_slot((0.0, length, 0.0))

    def envelope_box(self) -> Box:
        return figures.ROUND_FINGER_ENVELOPE


class RoundPalm(GLTFPart):
    """Manual ``RoundPalm(left, filename, length=1.4)``: five finger slots, the thumb's first."""

    type_name = "RoundPalm"
    physical = True

    def __init__(self, scene: Scene, node_id: str, left: bool, filename: str,
                 length: float = figures.ROUND_PALM_LENGTH) -> None:
        super().__init__(scene, node_id, filename, length)
        self.left = left
        for position, rotation, order in self.slot_figures(left, length):
            self.new_slot(position, rotation, order)

    def envelope_box(self) -> Box:
        return figures.palm_envelope(self.left, self.slot_figures(self.left, self.length))

    @staticmethod
    def slot_figures(left: bool, length: float) -> list[figures.SlotFigure]:
        return figures.round_palm_slots(left, length)


class AnthroPalm(RoundPalm):
    """Manual ``AnthroPalm(left, filename, length=1.4)``: the round palm cut for the thumb."""

    type_name = "AnthroPalm"

    @staticmethod
    def slot_figures(left: bool, length: float) -> list[figures.SlotFigure]:
        return figures.anthro_palm_slots(left, length)


class AnthroThumb(GLTFPart):
    """Manual ``AnthroThumb(left, filename, length=1.4)``: not raised; one slot for its finger."""

    type_name = "AnthroThumb"
    physical = True

    def __init__(self, scene: Scene, node_id: str, left: bool, filename: str,
                 length: float = figures.ROUND_PALM_LENGTH) -> None:
        super().__init__(scene, node_id, filename, length)
        self.left = left
        self.new_slot(*figures.anthro_thumb_slot(left, length))

    @property
    def offset(self) -> Vec3:
        return (0.0, 0.0, 0.0)
