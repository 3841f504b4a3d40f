"""Where robots' bases go, and (dynamic mode) where their mounts hold them.

A dynamic robot is held by a mount (a constraint) where its script put it; its node
carries where the physics put it, a little away when a hand is loaded. Kinematic mode and
anything but a robot: the base goes where its node is.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Mapping

from ..model.node import Node
from ..model.structure import base_pose
from ..physics.engine import PhysicsWorld

if TYPE_CHECKING:
    from ..kit.math3d import Pose


def mount_of(physics: PhysicsWorld, node: Node) -> Pose | None:
    """Dynamic mode: where a robot's mount holds it; the first time it is built in a
    dynamic world, where its node is (so a script that puts it where it is, tick after
    tick, holds it as one that does not: its node turned with the physics, and the first
    put turned the mount to that). None: not a robot, or kinematic mode."""
    if physics.dynamics is None or not node.lists_motors:
        return None
    if node.mount is None:  # type: ignore[attr-defined]
        node.mount = base_pose(node)  # type: ignore[attr-defined]
    return node.mount  # type: ignore[attr-defined,no-any-return]


def move_base(physics: PhysicsWorld, root_id: str, node: Node, fields: set[str]) -> None:
    """Put a root's base where its node is, its ``fields`` (position, quaternion) set. A
    dynamic robot's node carries where the physics put it (a loaded hand turns a little
    at its mount): what the script did not set keeps its mount's value, or a held weight
    would tip the hand further at every setPosition."""
    pose = base_pose(node)
    mount = mount_of(physics, node)
    if mount is not None:
        pose = (pose[0] if "position" in fields else mount[0],
                pose[1] if "quaternion" in fields else mount[1])
    physics.move_base(root_id, pose)
    if mount is not None:
        node.mount = pose  # type: ignore[attr-defined]


def hold_mounts(physics: PhysicsWorld, nodes: Mapping[str, Node]) -> None:
    """Dynamic mode: every built robot's mount put at once where its node's mount is:
    where a document restored it (after its tree was built where its node is), or where
    the robot is, for one moved into a new world (a mount first set at the next
    setPosition took the turn the physics had given the node by then, and a script's hand
    went one way or another as that came a tick sooner or later)."""
    for root_id in physics.roots():
        node = nodes.get(root_id)
        mount = None if node is None else mount_of(physics, node)
        if mount is not None:
            physics.place_mount(root_id, mount)
