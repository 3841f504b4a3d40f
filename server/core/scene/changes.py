"""Which nodes changed, and how, since a change set was opened."""

from __future__ import annotations


class ChangeSet:
    """Ids of nodes that were born, died, turned, moved or got new properties (and warnings).

    It stores only ids and field names; the values are read from the scene when the
    change set is collected, so a change undone by a failed batch costs nothing more
    than an idle re-send of the current value.
    """

    def __init__(self) -> None:
        self.born: dict[str, None] = {}
        self.died: set[str] = set()
        self.angles: dict[str, None] = {}
        self.poses: dict[str, None] = {}
        self.updates: dict[str, set[str]] = {}
        self.scene: set[str] = set()  # scene-level fields changed: camera, physics, caption
        self.warnings: list[str] = []  # what the requester should know, though nothing failed

    def update(self, node_id: str, field: str) -> None:
        """Note a changed property (``children`` when the order of a node's children changed)."""
        self.updates.setdefault(node_id, set()).add(field)

    def __bool__(self) -> bool:
        """True once anything changed (warnings aside)."""
        return bool(self.born or self.died or self.angles or self.poses or self.updates
                    or self.scene)

    def clear(self) -> None:
        """Forget everything noted so far."""
        self.__init__()
