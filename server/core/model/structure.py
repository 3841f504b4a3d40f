"""A tree of nodes compiled into an :class:`~server.core.physics.articulation.Articulation`.

Node poses compose as :meth:`Node.world_pose` composes them (a parent's world scale
stretches where its children sit; a part's shape takes the product of the scales above),
so the multibody puts every part where the tree does. Motors become joints; a joint rides
on the link of the one part it turns when only that part (and nothing turning) hangs
below it before the next part, and on a link of its own otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..kit import math3d
from ..kit.math3d import Pose, Vec3
from ..physics.articulation import NO_POSE, Articulation, Joint, Link
from ..physics.geometry import scaled
from .node import UNIT_SCALE, Node


@dataclass
class _Place:
    """Where the walk stands: the link it is on and a joint not given a link yet."""

    link: int                               # the link (−1: the base) poses are relative to
    pending: tuple[Joint, Pose] | None = None  # a joint and its origin, waiting for its part


def structure_of(root: Node) -> Articulation:
    """The articulation of the tree below ``root`` (a root: no parent)."""
    links: list[Link] = []
    base_scale = root.scale
    geometry = _collision_geometry(root, base_scale)
    _walk(root, _Place(-1), NO_POSE, base_scale, links)  # a root motor's turn: in the base pose
    return Articulation(root.id, root.id if geometry is not None else None, geometry,
                        tuple(links), base_scale, getattr(root, "mass", None),
                        getattr(root, "friction", None), mounted=root.lists_motors,
                        static=bool(getattr(root, "static", False)) or root.is_motor)


def base_pose(root: Node) -> Pose:
    """The world pose of the base: the root's own pose (a motor's turn included)."""
    return root.local_pose()


def _walk(node: Node, place: _Place, frame: Pose, scale: Vec3, links: list[Link]) -> None:
    """Compile the children of ``node``, whose frame is ``frame`` relative to the place's
    link (or to its pending joint's frame) and whose world scale is ``scale``."""
    for child in node.children:
        position = child.position if scale == UNIT_SCALE else \
            tuple(p * s for p, s in zip(child.position, scale))
        before = math3d.compose(frame, (position, child.quaternion))  # before its own turn
        child_scale = scale if child.scale == UNIT_SCALE else \
            tuple(a * s for a, s in zip(scale, child.scale))
        if child.is_motor:
            _motor(child, place, before, child_scale, links)
        elif child.physical and child.in_scene():
            link = _add(links, place, before, child, _collision_geometry(child, child_scale),
                        child_scale)
            _walk(child, _Place(link), links[link].shape, child_scale, links)  # the part's frame
        else:
            _walk(child, place, before, child_scale, links)


def _motor(motor: Any, place: _Place, before: Pose, scale: Vec3, links: list[Link]) -> None:
    """A motor: its joint rides on the one part it turns, or on a link of its own."""
    joint = Joint(motor.id, _axis(motor.axis, motor.flipped), motor.min, motor.max, motor.slides)
    if place.pending is not None:  # two joints meet: the first gets a link of its own
        place = _Place(_add(links, place, NO_POSE, None, None))
    stops = _stops(motor)
    if motor.physical or len(stops) != 1 or not stops[0].physical or stops[0].is_motor:
        if not stops and not motor.physical:
            return  # nothing physical turns with it: no link needed
        link = _add(links, _Place(place.link, (joint, before)), NO_POSE,
                    motor if motor.physical else None,
                    _collision_geometry(motor, scale) if motor.physical else None, scale)
        _walk(motor, _Place(link), NO_POSE, scale, links)
    else:
        _walk(motor, _Place(place.link, (joint, before)), NO_POSE, scale, links)


def _add(links: list[Link], place: _Place, frame: Pose, part: Node | None,
         geometry: dict[str, Any] | None, scale: Vec3 = UNIT_SCALE) -> int:
    """A new link at ``frame`` relative to the place (through its pending joint if any),
    carrying ``part`` (with its mass and friction, when it was given any)."""
    carried = {} if part is None else _carried(part, scale)
    part_id = None if part is None else part.id
    if place.pending is not None:
        joint, origin = place.pending
        links.append(Link(place.link, origin, joint, part_id, frame, geometry, scale, **carried))
    else:
        links.append(Link(place.link, frame, None, part_id, NO_POSE, geometry, scale, **carried))
    return len(links) - 1


_CARRIED = ("mass", "friction", "centre", "inertia")  # a part's figures its link keeps


def _carried(part: Node, scale: Vec3) -> dict[str, Any]:
    """A part's figures its link keeps, its centre of mass and inertia (a robot file's, in
    the file's lengths) stretched as its shape is: the inertia by the square of the
    scale's mean (exact for the uniform scale a robot file is placed with)."""
    carried = {name: getattr(part, name, None) for name in _CARRIED}
    if scale != UNIT_SCALE:
        centre, inertia = carried["centre"], carried["inertia"]
        if centre is not None:
            carried["centre"] = tuple(c * s for c, s in zip(centre, scale))
        if inertia is not None:
            squared = abs(scale[0] * scale[1] * scale[2]) ** (2 / 3)
            carried["inertia"] = tuple(i * squared for i in inertia)
    return carried


def _stops(motor: Node) -> list[Node]:
    """The first physical parts and motors below a motor (through bare nodes)."""
    stops, stack = [], list(motor.children)
    while stack:
        node = stack.pop()
        if node.is_motor or (node.physical and node.in_scene()):
            stops.append(node)
        else:
            stack.extend(node.children)
    return stops


def _axis(axis: math3d.Axis, flipped: bool) -> Vec3:
    unit = math3d.unit_axis(axis)
    return tuple(-v for v in unit) if flipped else unit


def _collision_geometry(node: Node, scale: Vec3) -> dict[str, Any] | None:
    if not (node.physical and node.in_scene()):
        return None
    geometry = node.geometry()
    return geometry if scale == UNIT_SCALE else scaled(geometry, scale)
