"""The objects a task hands to a hand: SHAP-like test objects, in a human hand's metres
and kilograms, made at a hand's scale."""

from __future__ import annotations

from dataclasses import dataclass

from ..objects import Ball, Box, Part, SceneMesh
from ..session import Session
from .scale import Scale


@dataclass(frozen=True)
class TestObject:
    """A test object: its shape, its size ``(x, y, z)`` in metres (a sphere's diameter; a
    cylinder lies along x) and its light and heavy masses in kilograms."""

    name: str
    shape: str  # sphere, cube, box or cylinder
    size: tuple[float, float, float]
    light: float
    heavy: float
    color: str

    def make(self, session: Session, scale: Scale) -> Part:
        """The object at the hand's scale, in ``session`` (not placed yet)."""
        x, y, z = (scale.length(v) for v in self.size)
        if self.shape == "sphere":
            return Ball(x / 2, self.color, scene=session)
        if self.shape == "cylinder":  # three.js cylinders stand along y: the task turns it
            return SceneMesh({"kind": "cylinder", "radiusTop": y / 2, "radiusBottom": y / 2,
                              "height": x, "segments": 24}, self.color, scene=session)
        return Box(x, y, z, self.color, scene=session)

    @property
    def extent(self) -> float:
        """Its largest size (slip is measured against it)."""
        return max(self.size)


# SHAP's six grip patterns with an object each (sizes and masses of the kind SHAP uses).
SPHERE = TestObject("sphere", "sphere", (0.055, 0.055, 0.055), 0.05, 0.3, "orange")
CUBE = TestObject("cube", "cube", (0.04, 0.04, 0.04), 0.04, 0.25, "steelblue")
CYLINDER = TestObject("cylinder", "cylinder", (0.11, 0.045, 0.045), 0.08, 0.45, "seagreen")
PLATE = TestObject("thin plate", "box", (0.006, 0.05, 0.07), 0.02, 0.12, "goldenrod")
TIP = TestObject("tip-pinch object", "cube", (0.016, 0.016, 0.016), 0.005, 0.03, "crimson")
CARD = TestObject("card", "box", (0.085, 0.012, 0.055), 0.03, 0.15, "slateblue")
