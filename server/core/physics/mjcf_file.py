"""A compiled tree as an MJCF model, zipped with its mesh files: what takes a hand to MuJoCo.

Written, as the URDF is (:mod:`.urdf_file`), from the :class:`~.articulation.Articulation`
the server simulates: a body per link, nested as the links are, at the link's ``origin``;
a hinge at the body's origin about the joint's axis, limited as the motor is (radians);
the part as a geom at the link's ``shape`` (spheres and boxes as MuJoCo's own, the rest as
the OBJ hull Bullet collides with, and a drawn OBJ of a mesh part's triangles in group 2
that does not collide); each body's mass and inertia as the URDF gives them. A follower is
an ``<equality><joint>`` on its leader (``polycoef="offset ratio 0 0 0"``); every other
motor gets a ``<position>`` actuator with its torque as its force range. The base body
sits at the model's origin: place it at the robot's pose.
"""

from __future__ import annotations

import io
import math
import xml.etree.ElementTree as ET
import zipfile
from typing import Any, Mapping

import numpy as np

from ..kit.math3d import Pose, to_matrix
from .articulation import NO_POSE, Articulation
from .assets import AssetLibrary
from .urdf_file import Masses, drawn_mesh, file_stem, hull_mesh, inertial, link_names, obj_bytes, rgba

# Each position actuator gives its whole torque this far from its aim (MuJoCo's kp is the
# torque over it), and every joint carries a servo's rotor inertia and damping; the robot's
# own geoms do not collide with each other (contype 2, conaffinity 1: with the world only,
# as in the server's dynamic mode). Measured on the 1.0 hands at a human unit: with a kp of
# 50 N·m/rad, no armature and self-collision, MuJoCo's default step went unstable (NaN) in
# 0.02-0.4 s; with these, every joint holds within 0.04 rad of its aim.
POSITION_SPAN = 0.1  # rad
SLIDE_SPAN = 0.01  # m: a slide joint's (its actuator's force over it)
ARMATURE = 1e-4  # kg·m²
DAMPING = 0.01  # N·m·s/rad


def mjcf_zip(tree: Articulation, name: str, masses: Masses, torques: Mapping[str, float],
             assets: AssetLibrary, names: Mapping[str, str], follows: Mapping[str, tuple[str, float, float]]) -> bytes:
    """The zip of ``name/robot.xml`` and ``name/meshes/*.obj`` for ``tree`` (arguments as
    :func:`.urdf_file.urdf_zip`'s)."""
    files: dict[str, bytes] = {}
    model = ET.Element("mujoco", model=names.get(tree.root, name))
    ET.SubElement(model, "compiler", angle="radian", meshdir="meshes")
    defaults = ET.SubElement(model, "default")
    ET.SubElement(defaults, "joint", armature=repr(ARMATURE), damping=repr(DAMPING))
    ET.SubElement(defaults, "geom", contype="2", conaffinity="1")
    asset, world = ET.SubElement(model, "asset"), ET.SubElement(model, "worldbody")
    base_mass, link_masses = masses
    titles = link_names(tree, names)
    bodies = [_body(world, titles[0], NO_POSE, tree.base_geometry, NO_POSE, base_mass, asset, files, assets)]
    for k, link in enumerate(tree.links):
        body = _body(bodies[link.parent + 1], titles[k + 1], link.origin, link.geometry, link.shape,
                     link_masses[k], asset, files, assets)
        if link.joint is not None:
            limited = math.isfinite(link.joint.lower) and math.isfinite(link.joint.upper)
            joint = ET.Element("joint", name=names.get(link.joint.motor, link.joint.motor),
                               type="slide" if link.joint.slides else "hinge",
                               axis=_numbers(link.joint.axis), limited=str(limited).lower())
            if limited:
                joint.set("range", _numbers((link.joint.lower, link.joint.upper)))
            body.insert(0, joint)
        bodies.append(body)
    _couplings(model, tree, names, torques, follows)
    ET.indent(model)
    files["robot.xml"] = b'<?xml version="1.0"?>\n' + ET.tostring(model, encoding="utf-8")
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        for path, data in files.items():
            archive.writestr(f"{file_stem(name)}/{path}", data)
    return out.getvalue()


def _body(parent: ET.Element, name: str, origin: Pose, geometry: dict[str, Any] | None, shape: Pose,
          mass: float, asset: ET.Element, files: dict[str, bytes], assets: AssetLibrary) -> ET.Element:
    body = ET.SubElement(parent, "body", name=name, pos=_numbers(origin[0]), quat=_wxyz(origin[1]))
    at, inertia = inertial(geometry, shape, mass)
    turn = np.asarray(to_matrix(at[1]))
    inertia = turn @ inertia @ turn.T  # MuJoCo's fullinertia is in the body's axes
    ET.SubElement(body, "inertial", pos=_numbers(at[0]), mass=repr(float(mass)),
                  fullinertia=_numbers((inertia[0][0], inertia[1][1], inertia[2][2], inertia[0][1],
                                        inertia[0][2], inertia[1][2])))
    if geometry is not None:
        colour = _numbers(rgba(geometry.get("color")))
        place = {"pos": _numbers(shape[0]), "quat": _wxyz(shape[1])}
        kind = geometry["kind"]
        if kind == "sphere":
            ET.SubElement(body, "geom", type="sphere", size=repr(float(geometry["radius"])), rgba=colour, **place)
        elif kind == "box":
            ET.SubElement(body, "geom", type="box", size=_numbers(np.asarray(geometry["size"]) / 2),
                          rgba=colour, **place)
        else:
            stem = f"m{len(files)}"
            files[f"meshes/{stem}.obj"] = obj_bytes(hull_mesh(geometry))
            ET.SubElement(asset, "mesh", name=stem, file=f"{stem}.obj")
            drawn = drawn_mesh(geometry, assets)
            ET.SubElement(body, "geom", type="mesh", mesh=stem, rgba=colour,
                          **({"group": "3"} if drawn is not None else {}), **place)
            if drawn is not None:
                files[f"meshes/{stem}.drawn.obj"] = obj_bytes(drawn)
                ET.SubElement(asset, "mesh", name=f"{stem}.drawn", file=f"{stem}.drawn.obj")
                ET.SubElement(body, "geom", type="mesh", mesh=f"{stem}.drawn", contype="0",
                              conaffinity="0", group="2", mass="0", rgba=colour, **place)
    return body


def _couplings(model: ET.Element, tree: Articulation, names: Mapping[str, str],
               torques: Mapping[str, float], follows: Mapping[str, tuple[str, float, float]]) -> None:
    equality, actuators = ET.Element("equality"), ET.Element("actuator")
    for _, joint in tree.joints():
        title = names.get(joint.motor, joint.motor)
        span = SLIDE_SPAN if joint.slides else POSITION_SPAN
        if joint.motor in follows:
            leader, ratio, offset = follows[joint.motor]
            ET.SubElement(equality, "joint", joint1=title, joint2=names.get(leader, leader),
                          polycoef=_numbers((offset, ratio, 0.0, 0.0, 0.0)))
        else:
            torque = float(torques.get(joint.motor, 1.0))
            ET.SubElement(actuators, "position", name=title, joint=title, kp=repr(torque / span),
                          forcelimited="true", forcerange=_numbers((-torque, torque)))
    for element in (equality, actuators):
        if len(element):
            model.append(element)


def _numbers(values: Any) -> str:
    return " ".join(repr(float(v)) for v in values)


def _wxyz(quaternion: Any) -> str:
    x, y, z, w = quaternion
    return _numbers((w, x, y, z))
