"""The manual's Sensor: a pad that senses along its local +Y, and the contacts of its part."""

from __future__ import annotations

from typing import Any

from ..kit.math3d import Vec3
from . import part_figures
from .node import World
from .parts import Part
from .readings import Reading
from .watches import LASER


class Sensor(Part):
    """Manual ``Sensor(visible=true, laserColor)``: readings are exact for the scene as it is.

    A sensor has no collision body: rays pass through it. Collision readings are the
    contacts of the nearest part above it in the tree (the part it is attached to).
    """

    type_name = "Sensor"

    def __init__(self, scene: World, node_id: str, visible: bool = True,
                 laser_color: str | int | bool | None = None) -> None:
        super().__init__(scene, node_id)
        self.visible = visible
        if isinstance(laser_color, bool):
            laser_color = part_figures.LASER_COLOR if laser_color else None
        self.laser_color = laser_color
        if laser_color is not None:
            scene.watches.add(node_id, LASER)

    def constructor_args(self) -> list[Any]:
        return [self.visible, self.laser_color]

    def geometry(self) -> dict[str, Any] | None:
        return part_figures.sensor_pad()  # drawn or not as `visible` says (it may change)

    def properties(self) -> dict[str, Any]:
        return {**super().properties(), "laserColor": self.laser_color}

    def host(self) -> Part | None:
        """The part whose contacts this sensor reports: the nearest part above it."""
        node = self.parent
        while node is not None and not isinstance(node, Part):
            node = node.parent
        return node

    def reading(self) -> Reading:
        """All readings at once, for the scene as it is now."""
        return self.scene.bodies.read([self])[self.id]

    def sense_distance(self) -> float:
        """Manual ``senseDistance()``: to the first body along +Y, past 0.05; or Infinity."""
        return self.reading().distance

    def sense_touch(self) -> float:
        """Manual ``senseTouch()``: 1 - d/0.05 for a body d ≤ 0.05 away along +Y, else 0."""
        return self.reading().touch

    def sense_position(self) -> Vec3:
        """Manual ``sensePosition()``: the sensor's world position."""
        return self.world_pose()[0]

    def sense_objects(self) -> list[str]:
        """Manual ``senseObjects()``: ids of what the sensor's part touches ("ground" too)."""
        return self.scene.bodies.touching(self.host())

    def sense_force(self, other: Part | str | None = None) -> float:
        """Newtons pressing on the sensor's part at the last tick, summed over its contacts,
        or from ``other`` alone (a part or "ground"): a fingertip's force on what it holds,
        not on the table beside it (dynamic mode; 0 in kinematic mode, where nothing pushes)."""
        if other is None:
            return self.scene.bodies.forces.on(self.host())
        return self.reading().force_from(other if isinstance(other, str) else other.id)

    def sense_contacts(self) -> list[dict[str, Any]]:
        """What presses on the sensor's part at the last tick, body by body: each one's id
        ("ground" for the ground), normal force and friction force (N; dynamic mode,
        largest normal force first; none in kinematic mode)."""
        return [force.wire() for force in self.reading().contacts]

    def sense_collision(self) -> bool:
        """Manual ``senseCollision()``: whether the sensor's part touches anything."""
        return bool(self.sense_objects())

    def sense_object(self, other: Part | str) -> bool:
        """Manual ``senseObject(other)``: whether the sensor's part touches ``other``."""
        other_id = other if isinstance(other, str) else other.id
        return other_id in self.sense_objects()

    def watch(self, on: bool = True, *, client: str) -> None:
        """Carry (or stop carrying) this sensor's readings in every frame."""
        if on:
            self.scene.watches.add(self.id, client)
        else:
            self.scene.watches.remove(self.id, client)
