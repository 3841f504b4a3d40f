"""Coupled motors: followers that turn with their leader (``Motor.follow``).

A follower's angle is ``ratio·leader + offset`` (clamped to its own limits), set in the
same request as its leader's, as one joint of a linkage or a tendon. The index from leader
to followers is worked out again only when a coupling or the tree changed, and a scene
without couplings pays one comparison a turn.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Mapping

if TYPE_CHECKING:
    from ..model.motor import Motor
    from ..model.node import Node

Turns = list[tuple["Motor", "float | None"]]


class Couplings:
    """The followers of every leader of a scene's motors."""

    def __init__(self, nodes: Mapping[str, Node]) -> None:
        self._nodes = nodes
        self.count = 0  # motors that follow another, counted when a coupling changes
        self._version = 0
        self._index: tuple[tuple[int, int], dict[str, list[Motor]]] | None = None

    def changed(self) -> None:
        """A motor's ``following`` changed (set, freed or undone)."""
        self.count = sum(getattr(node, "following", None) is not None
                         for node in self._nodes.values())
        self._version += 1

    def expand(self, turns: Turns, tree_version: int) -> Turns:
        """``turns`` with each leader's followers after it (theirs after them), and
        without turns of followers, which move only with their leaders."""
        if not self.count:
            return turns
        index = self._followers(tree_version)
        expanded: Turns = []
        for motor, angle in turns:
            if motor.leader() is not None:
                continue
            expanded.append((motor, angle))
            value = motor.within_limits(angle)
            stack = [] if value is None else [(motor, value)]
            while stack:
                leader, at = stack.pop()
                for follower in index.get(leader.id, ()):
                    aim = follower.share_of(at)
                    expanded.append((follower, aim))
                    if aim is not None:
                        stack.append((follower, aim))
        return expanded

    def _followers(self, tree_version: int) -> dict[str, list[Motor]]:
        key = (tree_version, self._version)
        if self._index is None or self._index[0] != key:
            index: dict[str, list[Motor]] = {}
            for node in self._nodes.values():
                following = getattr(node, "following", None)
                if following is not None and node.leader() is not None:  # type: ignore[attr-defined]
                    index.setdefault(following[0], []).append(node)  # type: ignore[arg-type]
            self._index = (key, index)
        return self._index[1]
