"""A long task's progress on stderr: a bar of the scene seconds it has run of all it
will, with how fast (scene seconds per second: above 1 is faster than real time) and an
estimate of the time left (tqdm's). Tasks open one with :func:`shown`; :func:`~.trial.drive`
advances it a tick at a time, so every task shows one without counting on its own."""

from __future__ import annotations

import sys
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Iterator

from tqdm import tqdm

_bar: ContextVar[tqdm | None] = ContextVar("bar", default=None)


@contextmanager
def shown(seconds: float, what: str) -> Iterator[None]:
    """A bar for ``seconds`` of scene time, labelled ``what``, while the block runs (a
    task inside another one's block adds to that one's bar instead)."""
    if _bar.get() is not None:
        yield
        return
    bar = tqdm(total=round(seconds, 2), desc=what, unit=" scene-s", file=sys.stderr, dynamic_ncols=True,
               bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.0f}/{total:.0f} scene-s "
                          "[{elapsed}<{remaining}, {rate_noinv_fmt}]", mininterval=0.5)
    token = _bar.set(bar)
    try:
        yield
    finally:
        _bar.reset(token)
        bar.close()


class _Silent:
    """A bar nobody sees: tasks run side by side (``report``) add to one bar of their own."""

    total = n = 0.0

    def update(self, seconds: float) -> None:
        pass


@contextmanager
def silenced() -> Iterator[None]:
    """No bar for the tasks run in the block (this thread's)."""
    token = _bar.set(_Silent())  # type: ignore[arg-type]
    try:
        yield
    finally:
        _bar.reset(token)


def advance(seconds: float) -> None:
    """``seconds`` more of scene time run (nothing without a bar)."""
    bar = _bar.get()
    if bar is not None:  # the last tick of a drive may go a tick past the planned total
        bar.update(min(seconds, bar.total - bar.n))
