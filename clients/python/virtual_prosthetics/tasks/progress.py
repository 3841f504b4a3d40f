"""A long task's progress, on stderr and in every viewer of its scene.

On stderr: a bar of the scene seconds it has run of all it will, with how fast (scene
seconds per second: above 1 is faster than real time) and an estimate of the time left
(tqdm's). In the viewers: the scene's caption (``setCaption``), the task's name, its
scene time and what it runs now with its score so far (:func:`tell`). Tasks open both with
:func:`shown`; :func:`~.trial.drive` advances them a tick at a time and sends the caption
every :data:`CAPTION_TICKS`, so every task shows them without counting on its own."""

from __future__ import annotations

import sys
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Iterator

from tqdm import tqdm

from ..session import Session

CAPTION_TICKS = 15  # a caption a quarter of a scene second: a few bytes in a step's message


@dataclass
class _Caption:
    what: str
    total: float
    done: float = 0.0
    line: str = ""  # what the task runs now and its score so far

    def text(self) -> str:
        head = f"{self.what} · {min(self.done, self.total):.1f} of {self.total:.0f} scene-s"
        return f"{head}\n{self.line}" if self.line else head


_bar: ContextVar[tqdm | None] = ContextVar("bar", default=None)
_caption: ContextVar[_Caption | None] = ContextVar("caption", default=None)


@contextmanager
def shown(seconds: float, what: str) -> Iterator[None]:
    """A bar and a caption for ``seconds`` of scene time, labelled ``what``, while the
    block runs (a task inside another one's block adds to that one's bar instead)."""
    caption = _caption.set(_Caption(what, seconds))
    try:
        if _bar.get() is not None:
            yield
            return
        bar = tqdm(total=round(seconds, 2), desc=what, unit=" scene-s", file=sys.stderr,
                   dynamic_ncols=True, mininterval=0.5,
                   bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.0f}/{total:.0f} scene-s "
                              "[{elapsed}<{remaining}, {rate_noinv_fmt}]")
        token = _bar.set(bar)
        try:
            yield
        finally:
            _bar.reset(token)
            bar.close()
    finally:
        _caption.reset(caption)


class _Silent:
    """A bar nobody sees: tasks run side by side (``report``) add to one bar of their own."""

    total = n = 0.0

    def update(self, seconds: float) -> None:
        pass


@contextmanager
def silenced() -> Iterator[None]:
    """No bar for the tasks run in the block (this thread's); their captions stay."""
    token = _bar.set(_Silent())  # type: ignore[arg-type]
    try:
        yield
    finally:
        _bar.reset(token)


def advance(seconds: float) -> None:
    """``seconds`` more of scene time run (nothing without a bar)."""
    caption = _caption.get()
    if caption is not None:
        caption.done += seconds
    bar = _bar.get()
    if bar is not None:  # the last tick of a drive may go a tick past the planned total
        bar.update(min(seconds, bar.total - bar.n))


def tell(line: str) -> None:
    """What the task runs now and its score so far, for the caption's second line."""
    caption = _caption.get()
    if caption is not None:
        caption.line = line


def caption_to(session: Session) -> None:
    """Send the caption to the scene's viewers (nothing outside :func:`shown`)."""
    caption = _caption.get()
    if caption is not None:
        session.set_caption(caption.text())
