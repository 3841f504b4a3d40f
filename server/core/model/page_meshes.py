"""SceneMeshes: the meshes a page adds to its scene, as shared objects every viewer draws.

Not in the manual: 1.0 pages add plain three.js meshes (obstacles, markers) to
``getScene()``, and 1.0's sensors met them. The JavaScript client makes a ``SceneMesh`` of each
(:mod:`server.core.physics.geometry` lists the geometries); rays and contacts meet it like any part.
"""

from __future__ import annotations

from typing import Any

from ..physics import geometry
from . import part_figures
from .node import World
from .parts import Part


class SceneMesh(Part):
    """``SceneMesh(geometry, color)``: a mesh of its own geometry and colour; no slots."""

    type_name = "SceneMesh"
    physical = True
    listed = False  # not one of a robot's getParts(): 1.0 pages' meshes were not parts

    def __init__(self, scene: World, node_id: str, shape: dict[str, Any],
                 color: str | int = part_figures.DEFAULT_COLOR) -> None:
        limits = scene.limits  # checked before the node exists: a refusal leaves no trace
        self.shape = geometry.check(shape, "new SceneMesh, argument 0 (geometry)",
                                    limits.shape_vertices, limits.shape_triangles)
        super().__init__(scene, node_id)
        self.color = color

    def set_color(self, color: str | int) -> None:
        """The colour every viewer draws the shape in."""
        self._assign("color", color)

    def constructor_args(self) -> list[Any]:
        return [self.shape, self.color]

    def geometry(self) -> dict[str, Any]:
        return self.shape

    def properties(self) -> dict[str, Any]:
        # the colour beside the geometry, not in it: setColor sends the colour alone
        return {**super().properties(), "color": self.color}
