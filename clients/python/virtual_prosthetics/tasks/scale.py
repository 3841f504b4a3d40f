"""How a task's human-sized world is scaled to a 1.0 hand.

The 1.0 hands are about 18× a human hand. A task scales every length by ``s`` = the hand's
palm-to-tip length over :data:`HUMAN_HAND` (0.19 m), and gravity by the same ``s``: a fall
of ``s·h`` under ``s·g`` takes as long as a fall of ``h`` under ``g``, so motion looks real
at the scene's own speed. Densities stay as they are (mass × s³); forces are then × s⁴ and
torques × s⁵, and results are given back in a human hand's newtons.
"""

from __future__ import annotations

from dataclasses import dataclass

HUMAN_HAND = 0.19  # metres from the wrist crease to the tip of the middle finger
GRAVITY = 9.81


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
    """A human-sized world scaled to a hand (see the module's docstring)."""

    factor: float

    @classmethod
    def of(cls, hand: str) -> Scale:
        return cls(FIGURES[hand].length / HUMAN_HAND)

    def length(self, metres: float) -> float:
        return metres * self.factor

    def mass(self, kilograms: float) -> float:
        return kilograms * self.factor ** 3

    def torque(self, newton_metres: float) -> float:
        return newton_metres * self.factor ** 5

    @property
    def gravity(self) -> float:
        return GRAVITY * self.factor

    def human_force(self, scene_newtons: float) -> float:
        """A force of the scaled world in a human hand's newtons."""
        return scene_newtons / self.factor ** 4
