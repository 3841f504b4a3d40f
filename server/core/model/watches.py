"""Which sensors' readings every frame carries, and who asked for them.

A sensor is watched while at least one watcher holds it: a client that called
``watch()``, or the sensor's own laser (the viewers draw it from the readings).
Changes are journaled, so a failed batch watches nothing.
"""

from __future__ import annotations

from typing import Iterable

from ..kit.errors import LimitExceeded
from ..kit.journal import Journal

LASER = "laser"  # the watcher of a sensor that has a laser


class Watches:
    """Watchers by sensor id, with a cap on how many sensors are watched at once."""

    def __init__(self, journal: Journal, limit: int) -> None:
        self._journal = journal
        self._limit = limit
        self._watchers: dict[str, set[str]] = {}

    def __contains__(self, sensor_id: str) -> bool:
        return sensor_id in self._watchers

    def __len__(self) -> int:
        return len(self._watchers)

    def ids(self) -> list[str]:
        """The watched sensors, in the order they were first watched."""
        return list(self._watchers)

    def holders(self) -> dict[str, list[str]]:
        """Who watches each watched sensor (clients' ids, or the laser's)."""
        return {sensor: sorted(holders) for sensor, holders in self._watchers.items()}

    def add(self, sensor_id: str, watcher: str) -> None:
        """``watcher`` watches the sensor (again: no change)."""
        holders = self._watchers.get(sensor_id)
        if holders is None:
            if len(self._watchers) >= self._limit:
                raise LimitExceeded(f"at most {self._limit} sensors can be watched in a scene",
                                    limit=self._limit, object=sensor_id)
            holders = self._watchers[sensor_id] = set()
        if watcher not in holders:
            holders.add(watcher)
            self._journal.record(lambda: self._release(sensor_id, watcher))

    def remove(self, sensor_id: str, watcher: str) -> None:
        """``watcher`` stops watching the sensor (not watching: no change)."""
        if watcher in self._watchers.get(sensor_id, ()):
            self._release(sensor_id, watcher)
            self._journal.record(lambda: self.add(sensor_id, watcher))

    def _release(self, sensor_id: str, watcher: str) -> None:
        holders = self._watchers[sensor_id]
        holders.discard(watcher)
        if not holders:
            del self._watchers[sensor_id]

    def drop_watcher(self, watcher: str) -> None:
        """Forget everything ``watcher`` watched (a client left)."""
        for sensor_id in [s for s, holders in self._watchers.items() if watcher in holders]:
            self.remove(sensor_id, watcher)

    def forget(self, sensor_ids: Iterable[str]) -> None:
        """Drop sensors that no longer exist, whoever watched them."""
        for sensor_id in sensor_ids:
            self._watchers.pop(sensor_id, None)
