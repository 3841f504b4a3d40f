"""A robot of a scene as files other tools open: URDF and MJCF (zips with their meshes)
and GLB.

Both are written from the tree the scene's physics compiled and simulates
(:mod:`server.core.physics.articulation`), with the scene's figures for what the tree does
not carry: the motors' torques, the parts' masses, the parts' poses and recolours. Files
are SI: lengths in metres (the scene's unit), masses in kilograms, torques in N·m. What a file needs is taken from the scene (a :class:`UrdfJob` or
:class:`GlbJob`: quick), and the file is written from it elsewhere (meshing parts takes
seconds for a hand): the server writes files in a process beside the scenes, so that
a loop of exports never holds up a scene's ticks.
"""

from __future__ import annotations

import pickle
from collections import Counter
from dataclasses import dataclass

from typing import Any

from ..kit.errors import UnknownObject
from ..kit.ids import owner_of
from ..kit.math3d import Pose, Quat, Vec3, compose
from ..model.imported import ImportedRobot
from ..model.robot import Robot
from ..model.structure import base_pose, structure_of
from ..physics.articulation import NO_POSE, Articulation, stretched_pose
from ..physics.assets import AssetLibrary
from ..physics.glb_file import DrawnLink, DrawnPart, robot_glb_bytes
from ..physics.dynamics import tree_masses
from ..physics.mjcf_file import mjcf_zip
from ..physics.urdf_file import Masses, link_names, urdf_zip
from ..scene.scene import Scene
from .reports import robot_report


@dataclass(frozen=True)
class UrdfJob:
    """What a robot's URDF zip is written from."""

    tree: Articulation
    robot_id: str
    masses: Masses  # the base's and each link's (kg)
    torques: dict[str, float]
    names: dict[str, str]                          # node id -> its name in the file
    follows: dict[str, tuple[str, float, float]]   # follower id -> (leader id, ratio, offset)

    def write(self, assets: AssetLibrary) -> bytes:
        return urdf_zip(self.tree, self.robot_id, self.masses, self.torques, assets,
                        self.names, self.follows)


@dataclass(frozen=True)
class MjcfJob(UrdfJob):
    """What a robot's MJCF zip is written from (what its URDF is)."""

    def write(self, assets: AssetLibrary) -> bytes:
        return mjcf_zip(self.tree, self.robot_id, self.masses, self.torques, assets,
                        self.names, self.follows)


@dataclass(frozen=True)
class GlbJob:
    """What a robot's GLB is written from: its links' nodes as they are now."""

    name: str
    pose: Pose
    links: tuple[DrawnLink, ...]

    def write(self, assets: AssetLibrary) -> bytes:
        return robot_glb_bytes(self.name, self.pose, self.links, assets)


PLACED_OWNER = "api"  # owns robots placed through REST (never a client's id: those are c<n>)


def place_robot(scene: Scene, file: str, position: Vec3, quaternion: Quat) -> dict[str, Any]:
    """``POST /api/scenes/{scene}/robots``: the robot of an uploaded robot file, placed,
    shared (anyone may steer it) and kept (it stays when nobody is connected); its report."""
    taken = {node_id for node_id in scene.nodes if owner_of(node_id) == PLACED_OWNER}
    number = next(n for n in range(1, len(taken) + 2) if f"{PLACED_OWNER}.{n}" not in taken)
    robot = ImportedRobot(scene, f"{PLACED_OWNER}.{number}", file)
    robot.set_position(position)
    robot.set_quaternion(quaternion)
    robot.share()
    robot.keep()
    return robot_report(robot)


def urdf_job(scene: Scene, robot_id: str) -> UrdfJob:
    """``GET …/robots/{id}/urdf``: the zip of ``{id}/robot.urdf`` and its meshes; the base
    at the file's origin (load it at the robot's position and rotation)."""
    robot, tree = _compiled(scene, robot_id)
    motors = robot.get_motors()
    torques = {motor.id: motor.get_max_torque() for motor in motors}
    follows = {m.id: _following_in_metres(scene, m) for m in motors
               if m.following is not None and m.leader() is not None}
    unit = scene.physics.unit
    masses = tree_masses(tree, scene.physics.density, unit=unit)
    return UrdfJob(tree.in_metres(unit), robot.id, masses, torques, file_names(robot),
                   follows)  # type: ignore[arg-type]


def _file_value(scene: Scene, motor: Any) -> float:
    """A motor's value as files give it: an angle, or a slider's length in metres."""
    return motor.angle * (scene.physics.unit if motor.slides else 1.0)


def _following_in_metres(scene: Scene, motor: Any) -> tuple[str, float, float]:
    """A follower's (leader, ratio, offset) between values as files give them."""
    leader, ratio, offset = motor.following
    into = scene.physics.unit if motor.slides else 1.0
    out_of = scene.physics.unit if motor.leader().slides else 1.0
    return leader, ratio * into / out_of, offset * into


def file_names(robot: Robot) -> dict[str, str]:
    """What a robot's nodes are called in files: their names (a motor's ``setName``, an
    imported link's). A name several nodes share is qualified by the nearest node above
    with a name of its own ("Index finger proximal"), then numbered; a node without a name
    keeps its id. No two nodes get one name."""
    nodes = list(robot.walk())
    own = {n.id: n.name for n in nodes if isinstance(getattr(n, "name", None), str) and n.name}
    counts = Counter(own.values())
    names: dict[str, str] = {}
    used = {n.id for n in nodes}
    for node in nodes:
        name = own.get(node.id)
        if name is None:
            continue
        if counts[name] > 1:
            above = node.parent
            while above is not None and counts[own.get(above.id, name)] != 1:
                above = above.parent
            name = f"{own[above.id]} {name}" if above is not None else name
        unique, k = name, 1
        while unique in used and unique != node.id:
            k += 1
            unique = f"{name} {k}"
        names[node.id] = unique
        used.add(unique)
    return names


def glb_job(scene: Scene, robot_id: str) -> GlbJob:
    """``GET …/robots/{id}/glb``: the robot as one binary glTF, a node per link with its
    local transform (its motor's angle now), where it is now."""
    robot, tree = _compiled(scene, robot_id)
    tree = tree.in_metres(scene.physics.unit)
    names = file_names(robot)
    titles = link_names(tree, names)

    def drawn(part: str | None, geometry: Any, shape: Pose) -> DrawnPart | None:
        return None if part is None else DrawnPart(part, geometry, shape,
                                                   getattr(scene.nodes[part], "recolors", ()))
    links = [DrawnLink(f"{titles[0]} base", -1, NO_POSE, drawn(tree.base_part, tree.base_geometry, NO_POSE))] \
        if tree.base_part is not None else []
    first = len(links)
    for k, link in enumerate(tree.links):
        turn = NO_POSE if link.joint is None else \
            link.joint.motion(_file_value(scene, scene.nodes[link.joint.motor]))
        parent = link.parent + first if link.parent >= 0 else first - 1
        links.append(DrawnLink(titles[k + 1], parent, compose(link.origin, turn),
                               drawn(link.part, link.geometry, link.shape)))
    root = scene.nodes[tree.root]
    return GlbJob(names.get(root.id, root.id), stretched_pose(base_pose(root), scene.physics.unit),
                  tuple(links))


def packed(job: UrdfJob | GlbJob) -> bytes:
    """A job as the scene's process hands it over (its answers are bytes or JSON)."""
    return pickle.dumps(job)


def written(job: bytes, assets: AssetLibrary) -> bytes:
    """The file of a :func:`packed` job (in the process that writes files)."""
    unpacked: UrdfJob | GlbJob = pickle.loads(job)  # noqa: S301 (the server's own scene process made it)
    return unpacked.write(assets)


def robot_urdf(scene: Scene, robot_id: str) -> bytes:
    """:func:`urdf_job`, written here."""
    return urdf_job(scene, robot_id).write(scene.assets)


def robot_glb(scene: Scene, robot_id: str) -> bytes:
    """:func:`glb_job`, written here."""
    return glb_job(scene, robot_id).write(scene.assets)


def packed_urdf_job(scene: Scene, robot_id: str) -> bytes:
    return packed(urdf_job(scene, robot_id))


def mjcf_job(scene: Scene, robot_id: str) -> MjcfJob:
    """``GET …/robots/{id}/mjcf``: what the URDF is written from, written as MJCF."""
    return MjcfJob(**vars(urdf_job(scene, robot_id)))


def packed_mjcf_job(scene: Scene, robot_id: str) -> bytes:
    return packed(mjcf_job(scene, robot_id))


def robot_mjcf(scene: Scene, robot_id: str) -> bytes:
    """:func:`mjcf_job`, written here."""
    return mjcf_job(scene, robot_id).write(scene.assets)


def packed_glb_job(scene: Scene, robot_id: str) -> bytes:
    return packed(glb_job(scene, robot_id))


def _compiled(scene: Scene, robot_id: str) -> tuple[Robot, Articulation]:
    """The robot and its tree as the physics compiles it (the tree it builds at the next
    tick, when the robot changed since the last)."""
    robot = scene.nodes.get(robot_id)
    if not isinstance(robot, Robot):
        raise UnknownObject(f"no robot {robot_id[:80]!r} in scene {scene.name!r}", object=robot_id)
    return robot, structure_of(robot.root())
