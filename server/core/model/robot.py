"""Robots: roots of part trees, addressed through their motors in depth-first order."""

from __future__ import annotations

import copy
from typing import Any

from ..kit.errors import WrongType
from ..kit.ids import owner_of
from ..kit.math3d import Pose, Vec3
from ..physics.grip_map import grip_map
from .motor import Motor
from .node import Node, World
from .parts import Part
from .structure import structure_of


class Robot(Node):
    """A mechanism of parts; its motors, in depth-first pre-order, are its degrees of freedom.

    The part and motor lists follow the tree as it is now (1.0 cached them at the first
    call; here later attachments count).
    """

    type_name = "Robot"
    lists_motors = True
    leaves_when_hidden = True

    def __init__(self, scene: World, node_id: str) -> None:
        super().__init__(scene, node_id)
        self.gui: str | None = None
        self.shared = False  # others may steer it and attach their parts (ownership.py)
        # dynamic mode: where its mount holds it, as a script last put it (None: not built
        # in a dynamic world yet); its node's pose is where the physics has it (a loaded
        # hand turns a little at its mount), and documents keep both
        self.mount: Pose | None = None
        self._listing: tuple[int, list[Part], list[Motor], frozenset[str]] | None = None
        self._grip_map: tuple[Any, dict[str, Any]] | None = None  # (its tree as of, the map)

    # --- chains ------------------------------------------------------------------------

    def add_chain(self, *nodes: Node) -> Node | None:
        """Manual ``addChain(a, b, …)``: each node to slot 0 of the one before; the last."""
        for parent, part in zip(nodes, nodes[1:]):
            if not isinstance(part, Part):
                raise WrongType(f"addChain can only attach parts; {part.id} is a "
                                f"{part.type_name}", object=part.id)
            part.attach_to_slot(parent)
        return nodes[-1] if nodes else None

    def attach_chain(self, *parts: Part) -> Node | None:
        """Manual ``attachChain(a, b, …)``: ``addChain(this, a, b, …)``."""
        return self.add_chain(self, *parts)

    def share(self, on: bool = True) -> Robot:
        """Let other clients set this robot's motor angles and attach their own parts to it
        (not in the manual); returns the robot."""
        self._assign("shared", bool(on))
        return self

    def add_gui(self, title: str = "Robot") -> None:
        """Manual ``addGUI(title)``: ask the viewers for a motor panel."""
        self._assign("gui", title)

    # --- listings ----------------------------------------------------------------------

    def get_parts(self) -> list[Part]:
        """Manual ``getParts()``: every part below the robot, motors included."""
        return self._listed()[0]

    def get_motors(self) -> list[Motor]:
        """Manual ``getMotors()``: the motors in depth-first order; index = position."""
        return self._listed()[1]

    def motor_ids(self) -> frozenset[str]:
        """The ids of :meth:`get_motors` (a frame's angles leave out the motors of a robot
        it lists whole: a set union, not a test per motor)."""
        return self._listed()[2]

    def _listed(self) -> tuple[list[Part], list[Motor], frozenset[str]]:
        """Parts, motors and the motors' ids, listed again only when the scene's tree changed."""
        version = self.scene.tree_version
        if self._listing is None or self._listing[0] != version:
            parts = [n for n in self.walk() if isinstance(n, Part) and n.listed]
            motors = [p for p in parts if isinstance(p, Motor)]
            self._listing = (version, parts, motors, frozenset(m.id for m in motors))
        return self._listing[1:]

    def get_grip_map(self) -> dict[str, Any]:
        """Its digits, the motors that close each and how far, the digit that opposes the
        others and which way the hand faces, derived from its kinematics with its motors
        at their defaults (:mod:`server.core.physics.grip_map`); vectors in the robot's own
        frame (its position and rotation taken away), motors also by their index."""
        key = (self.scene.tree_version, self.scale)
        if self._grip_map is None or self._grip_map[0] != key:  # (a search: 0.3 s for some)
            motors = self.get_motors()
            wire = grip_map(structure_of(self), {motor.id: motor.default for motor in motors}).wire()
            index = {motor.id: i for i, motor in enumerate(motors)}
            for digit in wire["digits"]:
                for entry in (*digit["motors"], *digit["preshape"]):
                    entry["index"] = index[entry["motor"]]
            self._grip_map = (key, wire)
        return copy.deepcopy(self._grip_map[1])

    def get_sensors(self) -> list[Part]:
        """Manual ``getSensors()``: the sensors below the robot."""
        return [p for p in self.get_parts() if p.type_name == "Sensor"]

    # --- pose --------------------------------------------------------------------------

    def get_position(self) -> Vec3:
        """Manual ``getPosition()``."""
        return self.position

    def set_position(self, position: Vec3 | None = None) -> None:
        """Manual ``setPosition``; with no position the robot leaves the scene (kept)."""
        if position is None:
            self._assign("visible", False)
            return
        super().set_position(position)
        self._assign("visible", True)

    # --- angles ------------------------------------------------------------------------

    def get_angle(self, index: int) -> float:
        """Manual ``getAngle(index)``: 0 when there is no such motor."""
        motors = self.get_motors()
        return motors[index].angle if 0 <= index < len(motors) else 0.0

    def set_angle(self, index: int, angle: float | None) -> None:
        """Manual ``setAngle(index, angle)``: ignored when there is no such motor."""
        motors = self.get_motors()
        if 0 <= index < len(motors):
            motors[index].set_angle(angle)

    def get_angles(self) -> list[float]:
        """Manual ``getAngles()``."""
        return [m.angle for m in self.get_motors()]

    def get_speeds(self) -> list[float]:
        """Each motor's :meth:`~.motor.Motor.get_speed`, in the order of ``getMotors()``."""
        return [speed for speed, _ in self.scene.bodies.motor_motion(self.get_motors())]

    def get_torques(self) -> list[float]:
        """Each motor's :meth:`~.motor.Motor.get_torque`, in the order of ``getMotors()``."""
        return [torque for _, torque in self.scene.bodies.motor_motion(self.get_motors())]

    def set_angles(self, *angles: float | None) -> None:
        """Manual ``setAngles(a0, a1, …)``: None leaves a motor as it is; extras are ignored."""
        self.scene.turn(list(zip(self.get_motors(), angles)))

    @property
    def motors(self) -> list[str]:
        """Ids of the motors in index order: sent to clients, so none works it out again."""
        return [motor.id for motor in self.get_motors()]

    def properties(self) -> dict[str, Any]:
        return {"gui": self.gui, "motors": self.motors, "owner": owner_of(self.id),
                "shared": self.shared}
