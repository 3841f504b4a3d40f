"""A task's human-sized world in a scene's units.

Test objects are made at their real size: their metres over the scene's unit
(``setPhysics``' ``unit``, metres per scene unit; the default makes a 1.0 hand a human
hand's 0.19 m). A hand is evaluated at the size it has: a 1.0 hand at the default unit, a
robot file at its own metres. Masses, torques, gravity and the forces read back are SI as
they are (the server converts).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..session import Session

HUMAN_HAND = 0.19  # metres from the wrist crease to the tip of the middle finger


@dataclass(frozen=True)
class Scale:
    """A human-sized world in a scene of ``1 / factor`` metres per unit."""

    factor: float  # scene units per metre

    @classmethod
    def of(cls, session: Session) -> Scale:
        """The scale of ``session``'s scene as its physics say now."""
        return cls(1.0 / session.get_physics()["unit"])

    def length(self, metres: float) -> float:
        """Scene units of ``metres``."""
        return metres * self.factor

    def metres(self, length: float) -> float:
        """Metres of ``length`` scene units."""
        return length / self.factor

    @property
    def unit(self) -> float:
        """The scene's unit (metres per scene unit)."""
        return 1 / self.factor
