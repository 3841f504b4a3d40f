"""The scene's camera: where every viewer looks from and at (manual ``setCamera…``)."""

from __future__ import annotations

from typing import Callable

from ..kit.journal import Journal
from ..kit.math3d import Vec3
from ..model import part_figures


class Camera:
    """A position and a target, journaled; ``moved`` is called after every change."""

    def __init__(self, journal: Journal, moved: Callable[[], None]) -> None:
        self._journal = journal
        self._moved = moved
        self.position: Vec3 = part_figures.CAMERA_POSITION
        self.target: Vec3 = part_figures.CAMERA_TARGET

    def set(self, key: str, value: Vec3) -> None:
        """Move the ``position`` or the ``target``."""
        old = getattr(self, key)
        self._journal.record(lambda: self._put(key, old))
        self._put(key, tuple(value))

    def _put(self, key: str, value: Vec3) -> None:
        setattr(self, key, value)
        self._moved()

    def wire(self) -> dict[str, list[float]]:
        """The camera as messages and documents carry it."""
        return {"position": list(self.position), "target": list(self.target)}
