"""Robots from files: ``ImportedRobot(file)`` builds the robot an uploaded URDF or MJCF
describes (:mod:`server.core.physics.robot_description`) out of ordinary nodes.

Every link becomes a :class:`RobotLink` part (its file's meshes drawn, its collision
elements' envelope, its mass and inertia), every turning joint a :class:`Motor` about the
joint's axis, named as the joint and limited as it is, placed where the joint is; a fixed
joint places its link on its parent; a coupled joint follows its leader
(:meth:`Motor.follow`). The file's metres are the scene's size: the robot is scaled by one
over the scene's unit. Ids are ``<robot>/<k>`` in the order made, so a document makes the
same robot again from the file's name alone, as a hand from its constructor.
"""

from __future__ import annotations

from typing import Any

from ..physics.assets import MeshFile
from ..physics.robot_description import JointDescription, LinkDescription, RobotDescription
from .motor import Motor, Slider, clamp
from .node import Node, World
from .parts import Part
from .robot import Robot

LINK_COLOR = "lightgray"  # a link with an envelope and nothing drawn (shown as its hull)


class RobotLink(Part):
    """A link of an imported robot (made by its robot, not by clients)."""

    type_name = "RobotLink"
    physical = True

    def __init__(self, scene: World, node_id: str, link: LinkDescription) -> None:
        self.mesh: MeshFile | None = None if link.mesh is None else scene.assets.mesh(link.mesh)
        super().__init__(scene, node_id)
        self.physical = link.hull is not None  # type: ignore[misc]  # a link may only be drawn
        self.name = link.name
        self.hull = link.hull
        self.mass, self.friction = link.mass, link.friction
        self.centre, self.inertia = link.centre, link.inertia  # dynamic mode's, from the file

    def geometry(self) -> dict[str, Any] | None:
        envelope = {} if self.hull is None else {"points": [list(p) for p in self.hull]}
        if self.mesh is not None:
            return {"kind": "mesh", "url": self.mesh.url, "offset": [0.0, 0.0, 0.0],
                    "mirror": False, **envelope}
        if self.hull is not None:
            return {"kind": "convex", **envelope, "color": LINK_COLOR}
        return None

    def properties(self) -> dict[str, Any]:
        return {**super().properties(), "name": self.name}


class ImportedRobot(Robot):
    """``ImportedRobot(file)``: the robot of an uploaded robot file (``<hash>.robot``)."""

    type_name = "ImportedRobot"

    def __init__(self, scene: World, node_id: str, filename: str) -> None:
        description = scene.assets.robot(filename)  # refused before the node exists
        for link in description.links:  # so are links whose meshes are missing
            if link.mesh is not None:
                scene.assets.mesh(link.mesh)
        super().__init__(scene, node_id)
        # its file is in metres: at the scene's unit it keeps its size beside 1.0's hands
        # (a unit changed later leaves it as it came in; setScale still stretches it)
        self.scale = (1 / scene.physics.unit,) * 3
        self.filename = filename
        self.name = description.name
        self._made = 0
        self._build(description)

    def constructor_args(self) -> list[Any]:
        return [self.filename]

    def uploaded_files(self) -> list[str]:
        """The uploads the robot is made of: its file and its links' meshes."""
        description = self.scene.assets.robot(self.filename)
        return [self.filename, *(link.mesh for link in description.links if link.mesh)]

    def _next_id(self) -> str:
        self._made += 1
        return f"{self.id}/{self._made - 1}"

    def _build(self, description: RobotDescription) -> None:
        parts: list[Part] = []
        motors: dict[str, Motor] = {}
        for link in description.links:
            part = RobotLink(self.scene, self._next_id(), link)
            joint = link.joint
            holder: Node = self if link.parent < 0 else parts[link.parent]
            if joint is not None and joint.kind != "fixed":
                motor = self._motor(joint)
                motor.name = joint.name
                motor.max_torque = joint.effort or None  # (no effort: the default's)
                motor.position, motor.quaternion = joint.origin
                motor._link(holder)
                motors[joint.name] = motor
                holder = motor
            elif joint is not None:
                part.position, part.quaternion = joint.origin
            part._link(holder)
            parts.append(part)
        for coupling in description.couplings:
            follower, leader = motors[coupling.follower], motors[coupling.leader]
            into, out_of = self._length(follower), self._length(leader)
            follower.follow(leader, coupling.ratio * into / out_of, coupling.offset * into)

    def _motor(self, joint: JointDescription) -> Motor:
        """A joint's motor: a Slider for a prismatic joint, its limits (the file's metres)
        in scene units."""
        kind = Slider if joint.kind == "prismatic" else Motor
        into = self._length(kind)
        lower, upper = joint.lower * into, joint.upper * into
        return kind(self.scene, self._next_id(), joint.axis, lower, upper, clamp(0.0, lower, upper))

    def _length(self, motor: Motor | type[Motor]) -> float:
        """Scene units in one of the file's units of a motor's value (1 for an angle)."""
        return self.scale[0] if motor.slides else 1.0

    def properties(self) -> dict[str, Any]:
        return {**super().properties(), "name": self.name}
