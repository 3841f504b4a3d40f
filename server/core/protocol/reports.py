"""Read-only views of a scene for the REST API (plain JSON-ready dictionaries)."""

from __future__ import annotations

from typing import Any

from ..kit import math3d
from ..kit.ids import owner_of
from ..kit.numbers import encode_numbers
from ..model.motor import Motor
from ..model.robot import Robot
from ..model.sensor import Sensor
from ..scene.scene import Scene


def robots(scene: Scene) -> list[Robot]:
    """The scene's robots, in the order they were made."""
    return [node for node in scene.roots() if isinstance(node, Robot)]


def scene_summary(scene: Scene) -> dict[str, Any]:
    """Name, clock (and which client holds it paused, if one does), object and robot
    counts, camera and physics of a scene."""
    return {"name": scene.name, "time": scene.time, "seq": scene.seq,
            "pausedBy": scene.clock.paused_by,
            "objects": len(scene.nodes), "robots": len(robots(scene)),
            "bodies": len(scene.bodies),
            "camera": scene.camera.wire(), "physics": scene.get_physics()}


def robot_summary(robot: Robot) -> dict[str, Any]:
    """A robot in a list: id, type, position, motor count."""
    return {"id": robot.id, "type": robot.type_name, "name": getattr(robot, "name", None),
            "owner": owner_of(robot.id),
            "shared": robot.shared, "position": list(robot.position),
            "visible": robot.visible, "motors": len(robot.get_motors()),
            "parts": len(robot.get_parts())}


def motor_report(motor: Motor, index: int) -> dict[str, Any]:
    """One motor of a robot, in motor order."""
    return encode_numbers({"id": motor.id, "index": index, "type": motor.type_name,
                           "axis": motor.axis, "min": motor.min, "max": motor.max,
                           "angle": motor.angle, "name": motor.name, "flipped": motor.flipped,
                           "follows": None if motor.following is None else list(motor.following)})


def robot_report(robot: Robot) -> dict[str, Any]:
    """Everything about a robot: pose, parts, and motors in index order."""
    rotation = math3d.matrix_to_euler_xyz(math3d.to_matrix(robot.quaternion))
    return {**robot_summary(robot), "quaternion": list(robot.quaternion),
            "rotation": list(rotation), "gui": robot.gui,
            "parts": [{"id": p.id, "type": p.type_name, "name": getattr(p, "name", None),
                       "parent": p.parent.id if p.parent else None,
                       "world": {"position": list(p.world_pose()[0]),
                                 "quaternion": list(p.world_pose()[1])}}
                      for p in robot.get_parts()],
            "motors": [motor_report(m, i) for i, m in enumerate(robot.get_motors())],
            "sensors": [s.id for s in robot.get_sensors()]}


def sensor_report(sensor: Sensor, other: str | None = None) -> dict[str, Any]:
    """A sensor's six readings, exact for the scene as it is now.

    ``object`` (the manual's ``senseObject(other)``) is there when ``other`` is given.
    """
    reading = sensor.reading()
    host = sensor.host()
    out = {"id": sensor.id, "type": sensor.type_name, "part": host.id if host else None,
           "watched": sensor.id in sensor.scene.watches, "laserColor": sensor.laser_color,
           **reading.wire(), "collision": bool(reading.objects)}
    if other is not None:
        out["object"] = other in reading.objects
    return out


def contacts_report(scene: Scene) -> dict[str, Any]:
    """The pairs touching at the last tick."""
    return {"seq": scene.seq, "time": scene.time, "contacts": scene.bodies.contacts.wire()}
