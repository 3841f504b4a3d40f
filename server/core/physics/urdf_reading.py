"""A URDF robot read into a :class:`~.robot_description.RobotDescription`.

yourdfpy (the URDF model viser and others use) parses the file; what it does not read,
PyBullet's ``<contact><lateral_friction>``, is read from the same XML tree. The XML is
parsed without entities or a network (a ``DOCTYPE`` is refused), so a description cannot
reach a file by an entity either. Links are ordered from the root (the one link no joint
holds) down; revolute and continuous joints become motors, prismatic ones sliders, fixed
ones hold their link where they put it, ``<mimic>`` becomes a coupling, and floating and
planar joints are refused naming the joint.
"""

from __future__ import annotations

import io
import math
import re
from typing import Any, Callable

import numpy as np

from ..kit.errors import BadAsset
from ..kit.limits import Limits
from ..kit.math3d import Pose
from . import link_meshes
from .link_meshes import Element, MeshReader
from .robot_archive import RobotArchive
from .robot_description import (Coupling, JointDescription, LinkDescription, RobotDescription,
                                checked, diagonal_in)

MOTOR_JOINTS = {"revolute": "revolute", "continuous": "revolute", "prismatic": "prismatic",
                "fixed": "fixed"}
Store = Callable[[bytes], str]  # keeps a link's GLB; its upload's name


def read_urdf(archive: RobotArchive, limits: Limits, store: Store) -> RobotDescription:
    """The robot of the archive's URDF description; each link's GLB kept by ``store``."""
    import yourdfpy

    root = parse_xml(archive.files[archive.description], "URDF")
    if root.tag != "robot":
        raise BadAsset(f"a URDF's root element is <robot>, not <{root.tag}>")
    try:
        robot = yourdfpy.URDF._parse_robot(root)
    except Exception as error:  # yourdfpy raises ValueError, KeyError, AttributeError …
        raise BadAsset(f"the URDF does not read: {str(error)[:200]}") from None
    frictions = {link.get("name"): link.find("contact/lateral_friction") for link in root.findall("link")}
    order = _tree_order(robot)
    reader, materials = MeshReader(archive, limits), {m.name: m for m in robot.materials}
    index = {name: k for k, (name, _) in enumerate(order)}
    links = []
    for name, joint in order:
        link = next(l for l in robot.links if l.name == name)
        friction = frictions.get(name)
        links.append(_link(link, joint, index, reader, materials, store, limits,
                           None if friction is None else _float(friction.get("value"), name)))
    couplings = tuple(Coupling(j.name, j.mimic.joint, float(j.mimic.multiplier or 1.0),
                               float(j.mimic.offset or 0.0))
                      for j in robot.joints if j.mimic is not None)
    return checked(RobotDescription(robot.name or "robot", "urdf", tuple(links), couplings))


def parse_xml(data: bytes, what: str) -> Any:
    """The root element of an XML file, parsed without entities, DTDs or a network."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             huge_tree=False, remove_comments=True)
    try:
        tree = etree.parse(io.BytesIO(data), parser)
    except etree.XMLSyntaxError as error:
        if "Unsupported version" not in str(error):
            raise BadAsset(f"the {what} is not well-formed XML: {str(error)[:160]}") from None
        # files in the field say <?xml version="0.0"?> (PyBullet's minitaur): read as UTF-8
        return parse_xml(re.sub(rb"^\s*<\?xml[^>]*\?>", b"", data, count=1), what)
    if tree.docinfo.doctype:
        raise BadAsset(f"the {what} has a DOCTYPE; descriptions with DTDs or entities are not read")
    return tree.getroot()


def _tree_order(robot: Any) -> list[tuple[str, Any]]:
    """(link name, the joint holding it) from the root down, parents first."""
    children: dict[str, list[Any]] = {}
    held = set()
    for joint in robot.joints:
        if joint.type not in MOTOR_JOINTS:
            raise BadAsset(f"joint {joint.name!r} is {joint.type}: only revolute, continuous, "
                           f"prismatic and fixed joints are taken (a hand's joints turn or slide)")
        if joint.child in held:
            raise BadAsset(f"link {joint.child!r} is held by two joints: a robot is a tree")
        held.add(joint.child)
        children.setdefault(joint.parent, []).append(joint)
    names = [link.name for link in robot.links]
    roots = [name for name in names if name not in held]
    if len(roots) != 1:
        raise BadAsset(f"a URDF robot has one root link (held by no joint); this one has "
                       f"{len(roots)}: {', '.join(roots[:5])}")
    order, stack = [], [(roots[0], None)]
    while stack:
        name, joint = stack.pop()
        if name not in names:
            raise BadAsset(f"joint {joint.name!r} names link {name!r}, which the URDF lacks")
        order.append((name, joint))
        stack.extend((j.child, j) for j in reversed(children.get(name, [])))
    if len(order) != len(names):
        raise BadAsset("some links hang on no chain from the root link (a joint loop?)")
    return order


def _link(link: Any, joint: Any, index: dict[str, int], reader: MeshReader,
          materials: dict[str, Any], store: Store, limits: Limits,
          friction: float | None) -> LinkDescription:
    visuals = [Element(_shape(v.geometry, reader, link.name), _matrix(v.origin),
                       _rgba(v.material, materials)) for v in link.visuals]
    collisions = [Element(_shape(c.geometry, reader, link.name), _matrix(c.origin))
                  for c in link.collisions]
    glb = link_meshes.drawn(visuals, link.name, limits)
    inertial = link.inertial
    mass = centre = inertia = None
    if inertial is not None and inertial.mass is not None and inertial.mass > 0:
        placement = _matrix(inertial.origin)
        mass, centre = float(inertial.mass), tuple(float(c) for c in placement[:3, 3])
        if inertial.inertia is not None:  # the tensor about the centre, in the inertial frame
            inertia = diagonal_in(placement[:3, :3], np.asarray(inertial.inertia, dtype=float))
    return LinkDescription(
        link.name, index[joint.parent] if joint is not None else -1,
        None if joint is None else _joint(joint), None if glb is None else store(glb),
        link_meshes.envelope(collisions), mass, centre, inertia, friction)


def _joint(joint: Any) -> JointDescription:
    kind = MOTOR_JOINTS[joint.type]
    origin = _pose(_matrix(joint.origin))
    axis = np.asarray(joint.axis if joint.axis is not None else (1.0, 0.0, 0.0), dtype=float)
    if not np.isfinite(axis).all() or np.linalg.norm(axis) < 1e-9:
        raise BadAsset(f"joint {joint.name!r} has no usable axis: {axis.tolist()}")
    limit = joint.limit
    lower, upper = -math.inf, math.inf
    if joint.type in ("revolute", "prismatic") and limit is not None:
        lower = _float(limit.lower, joint.name, 0.0)
        upper = _float(limit.upper, joint.name, 0.0)
    effort = None if limit is None or limit.effort is None else _float(limit.effort, joint.name)
    return JointDescription(joint.name, kind, origin, tuple(float(a) for a in axis / np.linalg.norm(axis)),
                            min(lower, upper), max(lower, upper), effort)


def _shape(geometry: Any, reader: MeshReader, link: str) -> Any:
    if geometry is None:
        raise BadAsset(f"link {link!r} has an element without a geometry")
    if geometry.box is not None:
        return link_meshes.box(geometry.box.size)
    if geometry.sphere is not None:
        return link_meshes.sphere(geometry.sphere.radius)
    if geometry.cylinder is not None:
        return link_meshes.cylinder(geometry.cylinder.radius, geometry.cylinder.length)
    if geometry.mesh is not None:
        return reader.mesh(geometry.mesh.filename, geometry.mesh.scale)
    raise BadAsset(f"link {link!r} has an element of no shape URDF knows")


def _rgba(material: Any, materials: dict[str, Any]) -> tuple[float, ...] | None:
    if material is None:
        return None
    if material.color is None and material.name in materials:  # a robot-level material by name
        material = materials[material.name]
    color = material.color
    return None if color is None or color.rgba is None else tuple(float(c) for c in color.rgba)


def _matrix(origin: Any) -> np.ndarray:
    return np.eye(4) if origin is None else np.asarray(origin, dtype=float)


def _pose(matrix: np.ndarray) -> Pose:
    """A 4×4 placement as (position, quaternion x, y, z, w)."""
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(matrix[:3, :3]).as_quat()
    return (tuple(float(c) for c in matrix[:3, 3]), (float(x), float(y), float(z), float(w)))  # type: ignore[return-value]


def _float(value: Any, where: str, default: float | None = None) -> float:
    try:
        number = float(value if value is not None else default)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise BadAsset(f"{where}: {value!r} is not a number") from None
    if not math.isfinite(number):
        raise BadAsset(f"{where}: {value!r} is not a finite number")
    return number
