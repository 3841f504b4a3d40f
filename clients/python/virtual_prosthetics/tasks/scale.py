"""How a task's human-sized world is laid out around a 1.0 hand.

The 1.0 hands are about 18 scene units long; a task's scene is set to the unit
(``setPhysics``' ``unit``, metres per scene unit) that makes its hand exactly a human
hand's size: :data:`HUMAN_HAND` (0.19 m) over the hand's palm-to-tip length. Positions and
sizes are then the human metres over that unit (``Scale.length``); masses, torques,
gravity and the forces read back are SI as they are (the server converts).
"""

from __future__ import annotations

from dataclasses import dataclass

HUMAN_HAND = 0.19  # metres from the wrist crease to the tip of the middle finger


@dataclass(frozen=True)
class HandFigures:
    """Where a hand is, palm down (``set_rotation(-π/2, 0, 0)``), fingers straight and
    together, relative to its position: the server's geometry, predicted here so that a
    task can lay out its set-up before the hand exists (tests check them against the
    server's)."""

    length: float        # wrist (palm's back edge) to the farthest fingertip, along -z
    palm_x: float        # x of the palm's middle
    fingers_z: float     # z where the palm ends and the fingers begin
    palm_below: float    # how far the palm's underside is below the hand's position
    thumb_side: float    # +1: the thumb is on the +x side


FIGURES = {
    "edged": HandFigures(length=3.5, palm_x=0.0, fingers_z=-1.4, palm_below=0.15, thumb_side=1),
    "round": HandFigures(length=3.6, palm_x=-0.055, fingers_z=-1.5625, palm_below=0.15,
                         thumb_side=1),
    "anthro": HandFigures(length=3.6, palm_x=-0.025, fingers_z=-1.5625, palm_below=0.15,
                          thumb_side=1),
}


@dataclass(frozen=True)
class Scale:
    """A human-sized world at a hand's size (see the module's docstring)."""

    factor: float  # scene units per metre

    @classmethod
    def of(cls, hand: str) -> Scale:
        return cls(FIGURES[hand].length / HUMAN_HAND)

    def length(self, metres: float) -> float:
        """Scene units of ``metres``."""
        return metres * self.factor

    @property
    def unit(self) -> float:
        """The scene's unit (metres per scene unit) that makes the hand a human's size."""
        return 1 / self.factor
