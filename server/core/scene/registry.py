"""The scene's nodes by id, the ids it handed out, and the quotas on what it holds."""

from __future__ import annotations

from collections import Counter

from ..kit.errors import DuplicateId, LimitExceeded, UnknownObject
from ..kit.ids import IdBook, owner_of
from ..kit.journal import Journal
from ..kit.limits import Limits
from ..model.node import Node


class Registry:
    """Every node of one scene by id, with counts per owner and of physical parts.

    Not journaled itself: the scene records how to undo each admission and removal.
    """

    def __init__(self, name: str, limits: Limits, journal: Journal) -> None:
        self.name = name
        self.limits = limits
        self._journal = journal
        self.nodes: dict[str, Node] = {}
        self.ids = IdBook(journal, limits.client_names)
        self.owned: Counter[str] = Counter()  # objects per owner
        self.physical = 0  # physical parts, in the scene or not
        self._made = 0  # nodes made so far: each node's serial says when it was made

    def fresh_ids(self) -> None:
        """Forget every id handed out (journaled): a whole scene is about to be replaced."""
        old = self.ids
        self._journal.record(lambda: setattr(self, "ids", old))
        self.ids = IdBook(self._journal, self.limits.client_names)

    def admit(self, node: Node) -> None:
        """Take a newly made node: its id must be new and the quotas must have room."""
        if node.id in self.nodes:
            raise DuplicateId(f"id {node.id} is already in use in scene {self.name}",
                              object=node.id)
        self._check_room(node)
        if "/" not in node.id:
            self.ids.claim(node.id, self.name)
        self.nodes[node.id] = node
        node.serial = self._made = self._made + 1
        self._count(node, 1)

    def _check_room(self, node: Node) -> None:
        limits, owner = self.limits, owner_of(node.id)
        if len(self.nodes) >= limits.scene_objects:
            raise LimitExceeded(f"scene {self.name} holds the maximum of "
                                f"{limits.scene_objects} objects", limit="sceneObjects",
                                value=limits.scene_objects, object=node.id)
        if self.owned[owner] >= limits.client_objects:
            raise LimitExceeded(f"{owner} has the maximum of {limits.client_objects} objects "
                                f"in scene {self.name}", limit="clientObjects",
                                value=limits.client_objects, object=node.id)
        if node.physical and self.physical >= limits.scene_bodies:
            raise LimitExceeded(f"scene {self.name} holds the maximum of {limits.scene_bodies} "
                                f"physical parts", limit="sceneBodies",
                                value=limits.scene_bodies, object=node.id)

    def drop(self, node: Node) -> None:
        """Take a node out (deleted, or its making undone)."""
        del self.nodes[node.id]
        self._count(node, -1)

    def revive(self, node: Node) -> None:
        """Put a dropped node back (its deletion undone)."""
        self.nodes[node.id] = node
        self._count(node, 1)

    def _count(self, node: Node, step: int) -> None:
        owner = owner_of(node.id)
        self.owned[owner] += step
        if not self.owned[owner]:
            del self.owned[owner]
        self.physical += step if node.physical else 0

    def get(self, node_id: str) -> Node:
        """The node with this id, or :class:`UnknownObject` saying whether it ever was here."""
        try:
            return self.nodes[node_id]
        except KeyError:
            gone = self.ids.used(node_id) and node_id.split("/")[0] not in self.nodes
            fate = "was deleted from" if gone else "is not in"
            raise UnknownObject(f"object {node_id} {fate} scene {self.name}",
                                object=node_id) from None

    def left_behind(self, client_id: str) -> list[Node]:
        """What a client made and did not keep, its own objects only (not their slots or
        a hand's parts), in the order they were made."""
        return [node for node_id, node in self.nodes.items()
                if "/" not in node_id and owner_of(node_id) == client_id and not node.is_kept()]

    def in_order_made(self) -> list[Node]:
        """Every node in the order it was made (``nodes`` is not, once a deletion was undone)."""
        return sorted(self.nodes.values(), key=lambda node: node.serial)

    def roots(self) -> list[Node]:
        """Nodes without a parent."""
        return [n for n in self.nodes.values() if n.parent is None]
