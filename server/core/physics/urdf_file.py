"""A compiled tree as a URDF robot, zipped with its mesh files: what takes a hand to ROS,
PyBullet, MuJoCo or Isaac.

Written from the :class:`~.articulation.Articulation` the server simulates, never from a
second description: a URDF link per link (the base first), a joint per link (revolute for
a motor, ``continuous`` when the motor has no limits, fixed otherwise) at the link's
``origin``, the part at the link's ``shape``. URDF's link frame is the joint frame, as
PyBullet's is, so loading the file and setting the same angles puts every part where the
server has it. The base sits at the file's origin: load it at the robot's pose.

- Shapes: spheres and boxes as URDF's own; every other part (hulls, cylinders, mesh
  files, page triangles) as an OBJ file of the hull Bullet collides with, and, for a mesh
  file's part or page triangles, a second OBJ of the triangles a viewer draws.
- Lengths in metres, masses in kilograms (the tree is given in metres).
- Inertials: the part's mass (``setMass``, else its volume × the scene's density, as
  dynamic mode weighs it), at the centre of its volume, with the exact inertia of its
  shape (Bullet itself takes a hull's inertia from its bounding box and recomputes it on
  loading unless told ``URDF_USE_INERTIA_FROM_FILE``). A link or base without a part
  weighs what dynamic mode gives it (:func:`.dynamics.tree_masses`), as a ball of
  SHAPELESS_RADIUS.
- Limits: ``effort`` is the motor's torque (N·m); ``velocity`` is required by URDF but
  the server's motors have no speed limit: NO_SPEED_LIMIT says so.
- Colours: a part's colour as a material (CSS names, ``#hex``, ``0xRRGGBB``).
- Names: links as their parts' names, joints as their motors' (``setName``, an imported
  file's), each name once; the rest by id. A follower's joint carries ``<mimic>``.
"""

from __future__ import annotations

import copy
import io
import math
import warnings
import xml.etree.ElementTree as ET
import zipfile
from typing import TYPE_CHECKING, Any, Mapping

import numpy as np
import webcolors

from ..kit.math3d import IDENTITY, Pose, compose
from .articulation import NO_POSE, Articulation
from .assets import AssetLibrary, placed
from .geometry import centroid, solid_points, triangle_arrays

if TYPE_CHECKING:  # trimesh and scipy are imported where used: the web process imports
    import trimesh  # this module for its routes (half a second of every server's start)

Masses = tuple[float, list[float]]  # the base's and each link's (kg), as tree_masses weighs them
SHAPELESS_RADIUS = 0.01  # m: a link without a part is a ball of its mass this big
NO_SPEED_LIMIT = 1000.0  # rad/s written as every joint's URDF velocity limit
FAR_SLIDE = 1000.0  # m: the limits written for a sliding joint that has none
DEFAULT_RGBA = (0.8, 0.8, 0.8, 1.0)  # a part whose colour is not one URDF can say


def urdf_zip(tree: Articulation, name: str, masses: Masses, torques: Mapping[str, float],
             assets: AssetLibrary, names: Mapping[str, str] | None = None,
             follows: Mapping[str, tuple[str, float, float]] | None = None) -> bytes:
    """The zip of ``name/robot.urdf`` and ``name/meshes/*.obj`` for ``tree``; ``torques``
    are the motors' (by motor id), ``masses`` the base's and the links' (kg), ``names`` what links
    and joints are called (by node id; else the id), ``follows`` the followers' leaders,
    ratios and offsets (by motor id: ``<mimic>``)."""
    files = urdf_files(tree, name, masses, torques, assets, names or {}, follows or {})
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        for path, data in files.items():
            archive.writestr(f"{file_stem(name)}/{path}", data)
    return out.getvalue()


def urdf_files(tree: Articulation, name: str, masses: Masses, torques: Mapping[str, float],
               assets: AssetLibrary, given: Mapping[str, str] | None = None,
               follows: Mapping[str, tuple[str, float, float]] | None = None) -> dict[str, bytes]:
    """``robot.urdf`` and its mesh files, by path relative to the URDF."""
    files: dict[str, bytes] = {}
    given = given or {}
    robot = ET.Element("robot", name=given.get(tree.root, name))
    base_mass, link_masses = masses
    names = link_names(tree, given)
    robot.append(_link(names[0], tree.base_geometry, NO_POSE, base_mass, files, assets))
    for k, link in enumerate(tree.links):
        robot.append(_link(names[k + 1], link.geometry, link.shape, link_masses[k], files, assets))
        robot.append(_joint(k, tree, names, torques, given, follows or {}))
    ET.indent(robot)
    files["robot.urdf"] = b'<?xml version="1.0"?>\n' + ET.tostring(robot, encoding="utf-8")
    return files


def link_names(tree: Articulation, given: Mapping[str, str] | None = None) -> list[str]:
    """The URDF name of the base and of every link: its part's name (``given``) or id, else
    (a link where two joints meet) its motor's, with ``.link``."""
    given = given or {}
    base = tree.base_part or tree.root
    names = [given.get(base, base)]
    for k, link in enumerate(tree.links):
        if link.part is not None:
            names.append(given.get(link.part, link.part))
        else:
            motor = link.joint.motor if link.joint else str(k)
            names.append(f"{given.get(motor, motor)}.link")
    return names


def _link(name: str, geometry: dict[str, Any] | None, shape: Pose, mass: float,
          files: dict[str, bytes], assets: AssetLibrary) -> ET.Element:
    element = ET.Element("link", name=name)
    element.append(_inertial(geometry, shape, mass))
    if geometry is None:
        return element
    stem = f"meshes/{len(files)}"
    collision, visual = _shapes(geometry, stem, files, assets)
    for tag, shaped in (("visual", visual), ("collision", collision)):
        child = ET.SubElement(element, tag)
        child.append(_origin(shape))
        child.append(copy.deepcopy(shaped))
        if tag == "visual":
            material = ET.SubElement(child, "material", name=f"{name}.color")
            ET.SubElement(material, "color", rgba=" ".join(f"{c:g}" for c in rgba(geometry.get("color"))))
    return element


def _shapes(geometry: dict[str, Any], stem: str, files: dict[str, bytes],
            assets: AssetLibrary) -> tuple[ET.Element, ET.Element]:
    """The collision and visual ``<geometry>`` of a part (mesh files added to ``files``)."""
    kind = geometry["kind"]
    if kind == "sphere":
        shaped = _geometry("sphere", radius=f"{geometry['radius']!r}")
        return shaped, shaped
    if kind == "box":
        shaped = _geometry("box", size=" ".join(repr(float(s)) for s in geometry["size"]))
        return shaped, shaped
    files[f"{stem}.obj"] = obj_bytes(hull_mesh(geometry))
    collision = _geometry("mesh", filename=f"{stem}.obj")
    drawn = drawn_mesh(geometry, assets)
    if drawn is None:
        return collision, collision
    files[f"{stem}.drawn.obj"] = obj_bytes(drawn)
    return collision, _geometry("mesh", filename=f"{stem}.drawn.obj")


def _geometry(kind: str, **attributes: str) -> ET.Element:
    element = ET.Element("geometry")
    ET.SubElement(element, kind, **attributes)
    return element


def inertial(geometry: dict[str, Any] | None, shape: Pose, mass: float) -> tuple[Pose, np.ndarray]:
    """Where a link's mass sits (the centre of its part's volume, in the part's axes, in
    the link's frame) and its inertia tensor there (a ball of SHAPELESS_RADIUS without a part)."""
    if geometry is None:
        return compose(shape, ((0.0, 0.0, 0.0), IDENTITY)), np.eye(3) * (0.4 * mass * SHAPELESS_RADIUS ** 2)
    return compose(shape, (centroid(geometry), IDENTITY)), inertia_of(geometry, mass)


def _inertial(geometry: dict[str, Any] | None, shape: Pose, mass: float) -> ET.Element:
    """Mass at the centre of the part's volume, with its shape's inertia there."""
    element = ET.Element("inertial")
    at, inertia = inertial(geometry, shape, mass)
    element.append(_origin(at))
    ET.SubElement(element, "mass", value=repr(float(mass)))
    ET.SubElement(element, "inertia", **{f"i{a}{b}": repr(float(inertia[i][j])) for i, j, a, b in (
        (0, 0, "x", "x"), (0, 1, "x", "y"), (0, 2, "x", "z"), (1, 1, "y", "y"), (1, 2, "y", "z"),
        (2, 2, "z", "z"))})
    return element


def inertia_of(geometry: dict[str, Any], mass: float) -> np.ndarray:
    """The inertia tensor (kg·m²) of a solid part of ``mass`` about the centre of its
    volume, in its own axes: exact for spheres and boxes, of the hull for the rest."""
    kind = geometry["kind"]
    if kind == "sphere":
        return np.eye(3) * (0.4 * mass * geometry["radius"] ** 2)
    if kind == "box":
        x, y, z = geometry["size"]
        return np.diag([y * y + z * z, x * x + z * z, x * x + y * y]) * (mass / 12)
    hull = hull_mesh(geometry)
    return np.asarray(hull.moment_inertia) * (mass / hull.mass)  # trimesh: density 1


def hull_mesh(geometry: dict[str, Any]) -> trimesh.Trimesh:
    """The convex hull Bullet collides with, as a mesh."""
    import trimesh

    return trimesh.convex.convex_hull(np.asarray(solid_points(geometry), float))


def drawn_mesh(geometry: dict[str, Any], assets: AssetLibrary) -> trimesh.Trimesh | None:
    """The triangles a viewer draws for a part, when they are not its hull: a mesh file's
    (placed as the part places it: mirrored, offset, scaled) or a page's triangles."""
    import trimesh

    if geometry["kind"] == "triangles":
        vertices, faces = triangle_arrays(geometry)
        return trimesh.Trimesh(vertices, faces, process=False)
    if geometry["kind"] != "mesh":
        return None
    mesh = assets.mesh(geometry["url"])
    return trimesh.Trimesh(*placed(geometry, mesh.vertices, mesh.triangles), process=False)


def obj_bytes(mesh: trimesh.Trimesh) -> bytes:
    """A mesh as an OBJ file's bytes (no normals, no textures)."""
    import trimesh

    return trimesh.exchange.obj.export_obj(mesh, include_normals=False, include_texture=False,
                                           header=None).encode()


def _joint(k: int, tree: Articulation, names: list[str], torques: Mapping[str, float],
           given: Mapping[str, str], follows: Mapping[str, tuple[str, float, float]]) -> ET.Element:
    link = tree.links[k]
    joint = link.joint
    if joint is None:
        element = ET.Element("joint", name=f"{names[k + 1]}.fixed", type="fixed")
    else:
        limited = math.isfinite(joint.lower) and math.isfinite(joint.upper)
        element = ET.Element("joint", name=given.get(joint.motor, joint.motor),
                             type="prismatic" if joint.slides else "revolute" if limited else "continuous")
    ET.SubElement(element, "parent", link=names[link.parent + 1])
    ET.SubElement(element, "child", link=names[k + 1])
    element.append(_origin(link.origin))
    if joint is not None:
        ET.SubElement(element, "axis", xyz=" ".join(repr(float(a)) for a in joint.axis))
        limits = {"effort": repr(float(torques.get(joint.motor, 0.0))), "velocity": repr(NO_SPEED_LIMIT)}
        if limited:
            limits.update(lower=repr(float(joint.lower)), upper=repr(float(joint.upper)))
        elif joint.slides:  # a prismatic joint without limits could not move (0 to 0)
            limits.update(lower=repr(-FAR_SLIDE), upper=repr(FAR_SLIDE))
        ET.SubElement(element, "limit", **limits)
        if joint.motor in follows:
            leader, ratio, offset = follows[joint.motor]
            ET.SubElement(element, "mimic", joint=given.get(leader, leader),
                          multiplier=repr(float(ratio)), offset=repr(float(offset)))
    return element


def _origin(pose: Pose) -> ET.Element:
    """URDF's ``<origin>``: its rpy turns about the fixed X, then Y, then Z axes."""
    from scipy.spatial.transform import Rotation

    with warnings.catch_warnings():  # a quarter turn in pitch: scipy warns, the angles hold
        warnings.simplefilter("ignore", UserWarning)
        roll_pitch_yaw = Rotation.from_quat(pose[1]).as_euler("xyz")
    return ET.Element("origin", xyz=" ".join(repr(float(v)) for v in pose[0]),
                      rpy=" ".join(repr(float(v)) for v in roll_pitch_yaw))


def rgba(color: Any) -> tuple[float, float, float, float]:
    """A part colour as URDF's rgba in 0…1 (CSS names, ``#hex``, ``0xRRGGBB``, [r, g, b])."""
    try:
        if isinstance(color, int) and not isinstance(color, bool):
            return ((color >> 16 & 255) / 255, (color >> 8 & 255) / 255, (color & 255) / 255, 1.0)
        if isinstance(color, (list, tuple)) and len(color) == 3:
            return (float(color[0]), float(color[1]), float(color[2]), 1.0)
        if isinstance(color, str):
            rgb = webcolors.hex_to_rgb(color) if color.startswith("#") else webcolors.name_to_rgb(color)
            return (rgb.red / 255, rgb.green / 255, rgb.blue / 255, 1.0)
    except ValueError:
        pass
    return DEFAULT_RGBA


def file_stem(name: str) -> str:
    """A robot's id as a folder name in the zip (what a file system takes)."""
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in name).strip(".")
    return safe or "robot"
