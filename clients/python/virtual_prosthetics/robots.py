"""Robots and hands, and the classes that stand in for objects other code created."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from . import http_api, objects
from .objects import Node, Part, Shown
from .session import Session


class Robot(Shown):
    """Manual ``Robot``: subclass it and build the robot in ``__init__``.

    The motors, in depth-first order of the tree as it is now, are the robot's degrees of
    freedom: ``set_angles`` and ``get_angles`` use that order.
    """

    _type = "Robot"

    def __init__(self, *, scene: Session | None = None) -> None:
        self._create(scene)

    def attach_chain(self, *parts: Part) -> Part | None:
        """Manual ``attachChain(a, b, …)``: a chain from this robot; returns the last part."""
        self._call("attachChain", *parts)
        return parts[-1] if parts else None

    def add_chain(self, *parts: Node) -> Node | None:
        """Manual ``addChain(a, b, …)``: each part to slot 0 of the one before; the last."""
        self._call("addChain", *parts)
        return parts[-1] if parts else None

    def share(self, on: bool = True) -> Robot:
        """Let other clients set this robot's motor angles and attach their own parts to it
        (not in the manual; without it only this client changes the robot)."""
        self._call("share", on)
        return self

    def set_position(self, *position: Any) -> Robot:
        """Manual ``setPosition([x, y, z])`` or ``setPosition(x, y, z)``; with no position
        the robot leaves the scene until it is given one again. Returns the robot (1.0
        chains it: ``EdgedHand().set_position(-2, 0.5, 0).set_rotation(-1, -1, 0)``)."""
        self._call("setPosition", *position)
        return self

    def set_rotation(self, x: float, y: float, z: float, order: str = "XYZ") -> Robot:
        """Manual ``setRotation(x, y, z, order='XYZ')``: Euler angles; returns the robot."""
        self._call("setRotation", x, y, z, order)
        return self

    def export_urdf(self, path: str | Path) -> Path:
        """Write the robot as a URDF zip to ``path`` (not in the manual): ``{id}/robot.urdf``
        with links, joints (named by the motors' ids), limits, torques and inertials, and
        its meshes beside it; its base at the file's origin. Returns the path."""
        return self._export("urdf", path)

    def export_mjcf(self, path: str | Path) -> Path:
        """Write the robot as an MJCF zip to ``path`` (not in the manual): ``{id}/robot.xml``
        with bodies, hinges, limits, inertials, followers as joint equalities and a
        position actuator per leading motor, and its meshes; MuJoCo compiles it. Returns
        the path."""
        return self._export("mjcf", path)

    def export_glb(self, path: str | Path) -> Path:
        """Write the robot's look, as it is now, as a GLB file to ``path`` (not in the
        manual): its parts' meshes with their colours and world poses. Returns the path."""
        return self._export("glb", path)

    def _export(self, kind: str, path: str | Path) -> Path:
        self._scene.sync()  # the file shows this client's every earlier change
        data = http_api.request(self._scene, http_api.scene_path(self._scene, "robots", self.id, kind),
                                f"export_{kind}")
        target = Path(path)
        target.write_bytes(data)
        return target

    def add_gui(self, title: str = "Robot") -> None:
        """Manual ``addGUI(title)``: a motor panel in every viewer."""
        self._call("addGUI", title)

    def _listing(self, kind: str) -> list[Any]:
        def read(mirror: Any) -> list[str]:
            nodes = mirror.motors(self.id) if kind == "motors" else mirror.parts(self.id)
            return [n["id"] for n in nodes if kind != "sensors" or n["type"] == "Sensor"]
        return [self._scene.proxy(node_id) for node_id in self._scene.read(read)]

    def get_parts(self) -> list[Part]:
        """Manual ``getParts()``: every part, motors included."""
        return self._listing("parts")

    def get_motors(self) -> list[objects.Motor]:
        """Manual ``getMotors()``: the motors in index order."""
        return self._listing("motors")

    def get_sensors(self) -> list[Part]:
        """Manual ``getSensors()``."""
        return self._listing("sensors")

    def get_grip_map(self) -> dict[str, Any]:
        """Not in 1.0: the hand's digits, derived by the server from its kinematics with
        its motors at their defaults: each digit's tip, the motors that close it (``motor``
        id, ``index``, ``open`` and ``closed`` values, palm first), whether it opposes the
        others and, if it does, the motors that turn it to face them first (``preshape``);
        ``centre``, ``approach`` (the way the hand faces) and ``forward`` (palm to tips) in
        the robot's own frame. The schema's ``gripMap``. Asks the server."""
        return dict(self._scene.call(self.id, "getGripMap", (), wait=True))

    def get_position(self) -> list[float]:
        """Manual ``getPosition()``: [x, y, z]."""
        return list(self._state()["position"])

    def _angles(self) -> list[float]:
        return self._scene.read(lambda mirror: [m["angle"] for m in mirror.motors(self.id)])

    def get_angle(self, index: int) -> float:
        """Manual ``getAngle(index)``: 0 when there is no such motor."""
        angles = self._angles()
        return angles[index] if 0 <= index < len(angles) else 0.0

    def set_angle(self, index: int, angle: float | None) -> None:
        """Manual ``setAngle(index, angle)``: ignored without such a motor or for None."""
        self._call("setAngle", index, angle)

    def get_angles(self) -> list[float]:
        """Manual ``getAngles()``."""
        return self._angles()

    def get_speeds(self) -> list[float]:
        """Not in 1.0: each motor's speed at the last step (rad/s; a slider's scene
        units/s), in motor order (dynamic mode; 0 in kinematic mode). Asks the server."""
        return [float(v) for v in self._scene.call(self.id, "getSpeeds", (), wait=True)]

    def get_torques(self) -> list[float]:
        """Not in 1.0: the torque each motor drove with in the last step (N·m; a slider's
        force, N), in motor order (dynamic mode; 0 in kinematic mode). Asks the server."""
        return [float(v) for v in self._scene.call(self.id, "getTorques", (), wait=True)]

    def set_angles(self, *angles: float | None) -> None:
        """Manual ``setAngles(a0, a1, …)``: None leaves that motor as it is."""
        self._call("setAngles", *angles)


class ImportedRobot(Robot):
    """A robot from a robot file the server keeps (not in the manual): ``file`` is the name
    ``POST /api/robots`` answered; :func:`~virtual_prosthetics.load_robot` uploads a file
    and makes one. Its motors are named as the file's joints (``motor.get_name()``)."""

    _type = "ImportedRobot"

    def __init__(self, file: str, *, scene: Session | None = None) -> None:
        self._create(scene, file)


class Hand(Robot):
    """The hands' finger control (thumb 0, index 1, middle 2, ring 3, little 4)."""

    def __init__(self, is_left: bool = True, *, scene: Session | None = None) -> None:
        self._create(scene, is_left)

    def flex_finger(self, index: int, angle: float | None) -> None:
        """Manual ``flexFinger(index, angle)``."""
        self._call("flexFinger", index, angle)

    def flex_fingers(self, angle: float | None) -> None:
        """Manual ``flexFingers(angle)``."""
        self._call("flexFingers", angle)

    def spread_finger(self, index: int, angle: float | None) -> None:
        """Manual ``spreadFinger(index, angle)``."""
        self._call("spreadFinger", index, angle)

    def spread_fingers(self, angle: float, include_thumb: bool = False) -> None:
        """Manual ``spreadFingers(angle, includeThumb=false)``."""
        self._call("spreadFingers", angle, include_thumb)


class EdgedHand(Hand):
    """Manual ``EdgedHand(isLeft=true)``."""

    _type = "EdgedHand"


class RoundHand(Hand):
    """Manual ``RoundHand(isLeft=true)``: 20 motors, round parts recoloured grey."""

    _type = "RoundHand"


class AnthroHand(Hand):
    """Manual ``AnthroHand(isLeft=true)``: 22 motors, the thumb's six first."""

    _type = "AnthroHand"
