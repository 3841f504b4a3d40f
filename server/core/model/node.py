"""The transform tree: every robot, part, motor, slot and sensor is a :class:`Node`."""

from __future__ import annotations

from typing import Any, ClassVar, Iterator, Mapping, Protocol, Sequence

from ..kit.errors import Cycle, LimitExceeded
from ..kit import math3d
from ..kit.ids import owner_of
from ..kit.journal import Journal
from ..kit.limits import Limits
from ..kit.math3d import IDENTITY, ORIGIN, Pose, Quat, Vec3
from ..physics.assets import AssetLibrary
from ..physics.settings import Physics
from .watches import Watches

UNIT_SCALE: Vec3 = (1.0, 1.0, 1.0)


class Forces(Protocol):
    """What presses on parts (server/core/scene/part_forces.py)."""

    def on(self, part: Node | None) -> float: ...


class Bodies(Protocol):
    """What nodes ask of the scene's physical bodies (server/core/scene/bodies.py)."""

    forces: Forces

    def read(self, sensors: list[Node], exact: bool = True) -> dict[str, Any]: ...

    def touching(self, part: Node | None, exact: bool = True) -> list[str]: ...

    def motor_motion(self, motors: Sequence[Node]) -> list[tuple[float, float]]: ...


class World(Protocol):
    """What a node needs of the scene it lives in. :class:`~server.core.scene.scene.Scene` is the
    one; the model names only this, so its imports never lead back to the scene."""

    journal: Journal
    limits: Limits
    watches: Watches
    assets: AssetLibrary
    bodies: Bodies
    nodes: Mapping[str, Node]
    tree_version: int  # counts the tree's changes (robots list their parts again)
    physics: Physics  # kinematic or dynamic, and the options
    pose_epoch: int  # counts changes of any pose: world poses cached before it are stale

    def register(self, node: Node) -> None: ...

    def node_changed(self, node: Node, field: str) -> None: ...

    def reparented(self, node: Node, old_parent: Node | None) -> None: ...

    def turn(self, turns: Sequence[tuple[Any, float | None]]) -> None: ...

    def warn(self, text: str) -> None: ...


class Node:
    """A node of the scene's transform tree with a local pose relative to its parent.

    All state changes go through :meth:`_assign` and :meth:`_link`, which record how to
    undo them in the scene's journal and tell the scene what changed.
    """

    type_name: ClassVar[str] = "Node"
    physical: ClassVar[bool] = False
    is_motor: ClassVar[bool] = False  # turns what hangs on it (the scene reports its angle)
    lists_motors: ClassVar[bool] = False  # a root whose motor list follows its tree (robots)
    leaves_when_hidden: ClassVar[bool] = False  # a root that, hidden, takes its tree out

    def __init__(self, scene: World, node_id: str) -> None:
        self.scene = scene
        self.id = node_id
        self.parent: Node | None = None
        self.children: list[Node] = []
        self.slots: list[Slot] = []
        self.position: Vec3 = ORIGIN
        self.quaternion: Quat = IDENTITY
        self.scale: Vec3 = UNIT_SCALE
        self.visible = True  # drawn (a robot: in the scene, see Robot.set_position)
        self.kept = False  # stays when its owner leaves (keep)
        self._world: Pose | None = None
        self._epoch = -1  # the scene's pose_epoch when _world was worked out
        self._world_scale: Vec3 = UNIT_SCALE
        self._root: tuple[int, Node] | None = None  # (the scene's tree_version, root) of root()
        self.serial = 0  # when it was made: the scene's count of nodes made until then
        scene.register(self)

    # --- state changes -----------------------------------------------------------------

    def _assign(self, field: str, value: Any) -> None:
        """Set an attribute, journaled and reported to the scene."""
        old = getattr(self, field)
        if old == value:
            return
        self.scene.journal.record(lambda: self._put(field, old))
        self._put(field, value)

    def _put(self, field: str, value: Any) -> None:
        setattr(self, field, value)
        self.scene.node_changed(self, field)

    def _link(self, parent: Node | None, index: int | None = None) -> None:
        """Move this node under ``parent`` (at ``index``, default last), journaled."""
        if parent is not None:
            self._check_place(parent)
        old_parent = self.parent
        old_index = old_parent.children.index(self) if old_parent is not None else None
        self.scene.journal.record(lambda: self._relink(old_parent, old_index))
        self._relink(parent, index)

    def _check_place(self, parent: Node) -> None:
        """Refuse a parent that lies below this node, or one that makes the tree too deep."""
        if parent is self or self.is_ancestor_of(parent):
            raise Cycle(f"cannot attach {self.id} below itself (to {parent.id})",
                        object=self.id, parent=parent.id)
        limit = self.scene.limits.tree_depth
        depth = parent.tree_depth() + self.tree_height()
        if depth > limit:
            raise LimitExceeded(f"attaching {self.id} to {parent.id} makes a tree {depth} "
                                f"nodes deep; at most {limit}", limit="treeDepth", value=limit,
                                object=self.id)

    def _relink(self, parent: Node | None, index: int | None) -> None:
        old_parent = self.parent
        if old_parent is not None:
            old_parent.children.remove(self)
        self.parent = parent
        if parent is not None:
            parent.children.insert(len(parent.children) if index is None else index, self)
        self.scene.reparented(self, old_parent)

    # --- tree ----------------------------------------------------------------------------

    def is_ancestor_of(self, node: Node) -> bool:
        """True when ``node`` lies below this node."""
        walker = node.parent
        while walker is not None:
            if walker is self:
                return True
            walker = walker.parent
        return False

    def walk(self) -> Iterator[Node]:
        """This node and its descendants in depth-first pre-order (three.js ``traverse``)."""
        stack = [self]
        while stack:
            node = stack.pop()
            yield node
            stack.extend(reversed(node.children))

    def tree_depth(self) -> int:
        """Nodes from the root down to this one (a root is 1 deep)."""
        depth, node = 1, self
        while node.parent is not None:
            depth, node = depth + 1, node.parent
        return depth

    def tree_height(self) -> int:
        """Nodes from this one down to its deepest descendant (a leaf is 1 high)."""
        height, level = 0, [self]
        while level:
            height, level = height + 1, [c for n in level for c in n.children]
        return height

    def root(self) -> Node:
        """The topmost ancestor (the node itself when it has no parent); walked again only
        after the tree changed (every change of a parent counts in ``tree_version``)."""
        version, known = self.scene.tree_version, self._root
        if known is not None and known[0] == version:
            return known[1]
        node = self
        while node.parent is not None:
            node = node.parent
        self._root = (version, node)
        return node

    def add_slot_node(self, slot: Slot) -> None:
        """Make ``slot`` one of this node's slots (and its child), journaled."""
        slot.leave_slots()
        self.slots.append(slot)
        self.scene.journal.record(lambda: self._drop_slot(slot, journal=False))
        slot._link(self)

    def restore_slots(self, slots: list[Slot]) -> None:
        """Make ``slots`` (children of this node) its numbered slots, in order, journaled."""
        old = self.slots
        self.scene.journal.record(lambda: setattr(self, "slots", old))
        self.slots = list(slots)

    def _drop_slot(self, slot: Slot, journal: bool = True) -> None:
        index = self.slots.index(slot)
        self.slots.pop(index)
        if journal:
            self.scene.journal.record(lambda: self.slots.insert(index, slot))

    # --- pose ----------------------------------------------------------------------------

    def local_pose(self) -> Pose:
        """Pose relative to the parent (motors add their rotation to it)."""
        return self.position, self.quaternion

    def world_pose(self) -> Pose:
        """Pose in the scene, cached until any pose in the scene changes (reads are rare:
        ticks take poses from the engine, so a change costs nothing here).

        A parent's scale stretches where its children sit, as in three.js; their own
        shapes take the product of the scales above (:meth:`world_scale`), which is
        three.js's picture whenever no non-uniform scale sits above a turned child.
        """
        epoch = self.scene.pose_epoch
        if self._epoch != epoch:
            stale, node = [], self  # this node and its ancestors without a current pose
            while node is not None and node._epoch != epoch:
                stale.append(node)
                node = node.parent
            for node in reversed(stale):
                node._place_in_world()
                node._epoch = epoch
        return self._world  # type: ignore[return-value]  # placed above

    def _place_in_world(self) -> None:
        local, parent = self.local_pose(), self.parent
        if parent is None:
            self._world, self._world_scale = local, self.scale
            return
        above = parent._world_scale
        if above != UNIT_SCALE:
            local = (tuple(p * s for p, s in zip(local[0], above)), local[1])
        self._world = math3d.compose(parent._world, local)  # type: ignore[arg-type]  # placed first
        self._world_scale = above if self.scale == UNIT_SCALE else \
            tuple(a * s for a, s in zip(above, self.scale))  # type: ignore[assignment]

    def world_scale(self) -> Vec3:
        """The product of this node's scale and its ancestors' (what its shape is stretched by)."""
        self.world_pose()
        return self._world_scale

    def set_position(self, position: Vec3) -> None:
        """Manual ``setPosition``: the position relative to the parent."""
        self._assign("position", tuple(position))

    def set_rotation(self, x: float, y: float, z: float, order: str = "XYZ") -> None:
        """Manual ``setRotation``: Euler angles relative to the parent."""
        self._assign("quaternion", math3d.euler_to_quat(x, y, z, order))

    def set_quaternion(self, quaternion: Quat) -> None:
        """The rotation relative to the parent as a unit quaternion (not in the manual)."""
        self._assign("quaternion", tuple(quaternion))

    def set_scale(self, scale: Vec3) -> None:
        """Stretch the node's shape and where its descendants sit (three.js ``scale``)."""
        self._assign("scale", tuple(scale))

    def set_visible(self, visible: bool) -> None:
        """Draw the node and its descendants or not (three.js ``visible``); rays and
        contacts still meet its shapes, as 1.0's raycaster did. A robot out of sight is
        out of the scene instead (:meth:`in_scene`, as ``setPosition()`` takes it)."""
        self._assign("visible", visible)

    def in_scene(self) -> bool:
        """False for the parts of a robot taken out of the scene with ``setPosition()``:
        they keep their place in the tree, without bodies."""
        root = self.root()
        return root.visible or not root.leaves_when_hidden

    def keep(self, on: bool = True) -> Node:
        """Leave this object (and what hangs below it) in the scene when its owner leaves
        (not in the manual; a connection's ``keep`` does it for everything it makes)."""
        self._assign("kept", bool(on))
        return self

    def is_kept(self) -> bool:
        """True when this node, or one above it of the same owner, is kept (:meth:`keep`):
        a part attached to another client's kept robot still goes with its owner."""
        owner = owner_of(self.id)
        node: Node | None = self
        while node is not None and owner_of(node.id) == owner:
            if node.kept:
                return True
            node = node.parent
        return False

    # --- description ---------------------------------------------------------------------

    def describe(self) -> dict[str, Any]:
        """The node as the snapshot and ``added`` messages carry it."""
        return {"id": self.id, "type": self.type_name,
                "parent": self.parent.id if self.parent is not None else None,
                "children": [child.id for child in self.children],
                "position": list(self.position), "quaternion": list(self.quaternion),
                "scale": list(self.scale), "visible": self.visible, "kept": self.kept,
                **self.properties()}

    def properties(self) -> dict[str, Any]:
        """Type-specific fields of :meth:`describe`."""
        return {}

    def constructor_args(self) -> list[Any]:
        """Arguments of the manual's constructor that make this node again (as ``create``
        takes them, before :func:`~server.core.kit.numbers.encode_numbers`); what changed since
        is state (:mod:`server.core.protocol.scene_document`)."""
        return []


class Slot(Node):
    """A place on a part where other parts attach; its pose orients what attaches."""

    type_name = "Slot"

    def __init__(self, scene: World, node_id: str, position: Vec3 = ORIGIN) -> None:
        super().__init__(scene, node_id)
        self.position = tuple(position)

    def constructor_args(self) -> list[Any]:
        return [list(self.position)]

    def leave_slots(self) -> None:
        """Stop being one of the slots of the node it hangs on (it stays its child)."""
        if self.parent is not None and self in self.parent.slots:
            self.parent._drop_slot(self)
