"""Undo journal: how one operation, or a whole batch, applies completely or not at all."""

from __future__ import annotations

from contextlib import contextmanager
from typing import Callable, Iterator

Undo = Callable[[], None]


class Journal:
    """Collects undo steps while a transaction is open and replays them if it fails.

    Transactions nest by joining the outermost one: a batch of operations is one
    transaction, so a failure in its last operation also undoes its first.
    """

    def __init__(self) -> None:
        self._steps: list[Undo] | None = None

    @property
    def active(self) -> bool:
        """True while a transaction is open."""
        return self._steps is not None

    def record(self, undo: Undo) -> None:
        """Remember how to reverse a change just made (ignored outside a transaction)."""
        if self._steps is not None:
            self._steps.append(undo)

    @contextmanager
    def transaction(self) -> Iterator[None]:
        """Open a transaction; an exception inside it undoes every recorded change."""
        if self._steps is not None:
            yield
            return
        self._steps = []
        try:
            yield
        except BaseException:
            steps, self._steps = self._steps, None
            for undo in reversed(steps):
                undo()
            raise
        finally:
            self._steps = None
