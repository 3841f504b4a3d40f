"""The change feed: what changed since the last tick, and inside requests that asked."""

from __future__ import annotations

from contextlib import contextmanager
from typing import Iterable, Iterator

from .changes import ChangeSet


class ChangeFeed:
    """The tick's pending change set and any number of open recordings beside it.

    Every note goes to all of them: the tick sends its set to every client, a request's
    recording tells its requester what the request did (warnings included).
    """

    def __init__(self) -> None:
        self.pending = ChangeSet()
        self._recorders: list[ChangeSet] = [self.pending]

    def born(self, node_id: str) -> None:
        """A node was made."""
        for changes in self._recorders:
            changes.born[node_id] = None

    def died(self, node_id: str) -> None:
        """A node was deleted."""
        for changes in self._recorders:
            changes.died.add(node_id)

    def changed(self, node_id: str, field: str) -> None:
        """A node's field changed: a pose, an angle or another property."""
        for changes in self._recorders:
            if field in ("position", "quaternion"):
                changes.poses[node_id] = None
            elif field == "angle":
                changes.angles[node_id] = None
            else:
                changes.update(node_id, field)

    def turned(self, motor_ids: Iterable[str]) -> None:
        """Motors got new angles."""
        motor_ids = dict.fromkeys(motor_ids)
        for changes in self._recorders:
            changes.angles.update(motor_ids)

    def regrouped(self, parent_ids: list[str], robot_ids: list[str]) -> None:
        """The children of these parents and the motor lists of these robots changed."""
        for changes in self._recorders:
            for parent_id in parent_ids:
                changes.update(parent_id, "children")
            for robot_id in robot_ids:
                changes.update(robot_id, "motors")

    def scene_changed(self, field: str) -> None:
        """A scene-level field (``camera``, ``physics``, ``caption``) changed."""
        for changes in self._recorders:
            changes.scene.add(field)

    def warn(self, message: str) -> None:
        """Tell the open recordings' requesters; the tick's own set has no one to tell."""
        for changes in self._recorders[1:]:
            changes.warnings.append(message)

    @contextmanager
    def recording(self) -> Iterator[ChangeSet]:
        """Note, besides the tick's set, what changes inside this block."""
        changes = ChangeSet()
        self._recorders.append(changes)
        try:
            yield changes
        finally:
            self._recorders.remove(changes)
