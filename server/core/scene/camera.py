"""The scene's camera: where every viewer looks from and at (manual ``setCamera…``)."""

from __future__ import annotations

from typing import Any, Callable

from ..kit.journal import Journal
from ..kit.math3d import Vec3
from ..model import part_figures


class Camera:
    """A position and a target, journaled; ``moved`` is called after every change.

    ``placed`` is false until a script (or a document) sets either: viewers then frame
    what the scene holds rather than keep the manual's default view."""

    def __init__(self, journal: Journal, moved: Callable[[], None]) -> None:
        self._journal = journal
        self._moved = moved
        self.position: Vec3 = part_figures.CAMERA_POSITION
        self.target: Vec3 = part_figures.CAMERA_TARGET
        self.placed = False

    def set(self, key: str, value: Vec3) -> None:
        """Move the ``position`` or the ``target``."""
        self._put({key: tuple(value), "placed": True})

    def reset(self) -> None:
        """Back to the manual's default view, placed by no one (an imported scene's own)."""
        self._put({"position": part_figures.CAMERA_POSITION,
                   "target": part_figures.CAMERA_TARGET, "placed": False})

    def _put(self, fields: dict[str, Any]) -> None:
        old = {key: getattr(self, key) for key in fields}
        self._journal.record(lambda: self._assign(old))
        self._assign(fields)

    def _assign(self, fields: dict[str, Any]) -> None:
        for key, value in fields.items():
            setattr(self, key, value)
        self._moved()

    def wire(self) -> dict[str, Any]:
        """The camera as messages and documents carry it."""
        wire: dict[str, Any] = {"position": list(self.position), "target": list(self.target)}
        if not self.placed:
            wire["placed"] = False
        return wire
