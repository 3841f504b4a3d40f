"""The scene's caption: a few words every viewer shows in a corner (a task's name, trial,
time and score), set by a script (``setCaption``; not in the manual)."""

from __future__ import annotations

from typing import Callable

from ..kit.journal import Journal


class Caption:
    """The text, journaled; ``changed`` is called after every change ("" shows nothing)."""

    def __init__(self, journal: Journal, changed: Callable[[], None]) -> None:
        self._journal = journal
        self._changed = changed
        self.text = ""

    def set(self, text: str) -> None:
        """Show ``text`` (lines split at ``\\n``); "" hides the caption."""
        if text == self.text:
            return
        old = self.text
        self._journal.record(lambda: self._put(old))
        self._put(text)

    def _put(self, text: str) -> None:
        self.text = text
        self._changed()
