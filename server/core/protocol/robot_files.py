"""A robot of a scene as files other tools open: URDF (a zip with its meshes) and GLB.

Both are written from the tree the scene's physics compiled and simulates
(:mod:`server.core.physics.articulation`), with the scene's figures for what the tree does
not carry: the motors' torques, the density parts are weighed with, the parts' poses and
recolours.
"""

from __future__ import annotations

from ...errors import UnknownObject
from ..model.robot import Robot
from ..model.structure import structure_of
from ..physics.articulation import Articulation
from ..physics.glb_file import DrawnPart, glb_bytes
from ..physics.urdf_file import urdf_zip
from ..scene.scene import Scene


def robot_urdf(scene: Scene, robot_id: str) -> bytes:
    """``GET …/robots/{id}/urdf``: the zip of ``{id}/robot.urdf`` and its meshes; the base
    at the file's origin (load it at the robot's position and rotation)."""
    robot, tree = _compiled(scene, robot_id)
    torques = {motor.id: motor.get_max_torque() for motor in robot.get_motors()}
    return urdf_zip(tree, robot.id, scene.physics.density, torques, scene.assets)


def robot_glb(scene: Scene, robot_id: str) -> bytes:
    """``GET …/robots/{id}/glb``: the robot's parts as one binary glTF, where they are now."""
    _, tree = _compiled(scene, robot_id)
    geometries = ([tree.base_geometry] if tree.base_part is not None else []) + \
        [link.geometry for link in tree.links if link.part is not None]
    parts = []
    for key, geometry in zip(tree.parts(), geometries):
        node = scene.nodes[key]
        parts.append(DrawnPart(key, geometry, node.world_pose(),  # type: ignore[arg-type]
                               getattr(node, "recolors", ())))
    return glb_bytes(parts, scene.assets)


def _compiled(scene: Scene, robot_id: str) -> tuple[Robot, Articulation]:
    """The robot and its tree as the physics compiles it (the tree it builds at the next
    tick, when the robot changed since the last)."""
    robot = scene.nodes.get(robot_id)
    if not isinstance(robot, Robot):
        raise UnknownObject(f"no robot {robot_id[:80]!r} in scene {scene.name!r}", object=robot_id)
    return robot, structure_of(robot.root())
