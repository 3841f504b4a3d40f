"""A scene's clock held by a script: paused, the scene's time moves only when stepped.

A scene's clock normally follows the wall clock (the scene's process ticks it 60 times a
second). A trial that must come out the same however busy the server is (a hand-function
test, a re-run of a recording) pauses it and steps it: each ``step`` is whole ticks of
exactly one period, taken after the request that asked for them and before its answer
leaves, so the script reads the world those ticks made and sends its next commands
between two ticks, never during one. It runs as fast as the server can compute.
"""

from __future__ import annotations

from ..kit.errors import Forbidden, NotPaused, OutOfRange
from ..kit.journal import Journal

MAX_STEP_TICKS = 60  # a message's steps at most (a second): the scene still answers its others


class Clock:
    """Who paused the scene (a client id; None: it runs) and the ticks asked for by steps
    that the scene's loop has not taken yet."""

    def __init__(self, journal: Journal) -> None:
        self._journal = journal
        self.paused_by: str | None = None
        self.owed = 0

    @property
    def paused(self) -> bool:
        return self.paused_by is not None

    def pause(self, client: str) -> None:
        """Hold the clock (journaled: a failed batch that paused leaves it running). One
        client holds it at a time: two scripts stepping one scene would each take the
        other's ticks (two task runs in one scene laid their trials over each other)."""
        if self.paused_by not in (None, client):
            raise Forbidden(f"the scene's clock is held by {self.paused_by}, which paused it "
                            f"to step it; it runs again once {self.paused_by} resumes it or "
                            f"leaves: step a scene of your own", owner=self.paused_by)
        self._put(client)

    def resume(self) -> None:
        """Let the clock run with the wall clock again; steps not taken yet are dropped."""
        self._put(None)
        self.owed = 0

    def step(self, ticks: int) -> None:
        """Ask for ``ticks`` more ticks of the paused scene."""
        if self.paused_by is None:
            raise NotPaused("step advances a paused scene; call pause() first")
        if self.owed + ticks > MAX_STEP_TICKS:  # a batch of steps is no way round the bound
            raise OutOfRange(f"one message steps at most {MAX_STEP_TICKS} ticks; "
                             f"{self.owed} asked already, {ticks} more refused")
        before = self.owed
        self._journal.record(lambda: setattr(self, "owed", before))
        self.owed += ticks

    def take(self) -> int:
        """The ticks owed, now counted as taken."""
        owed, self.owed = self.owed, 0
        return owed

    def released(self, client: str) -> None:
        """A client left for good: a pause it held ends (a script that crashed does not
        freeze a shared scene)."""
        if self.paused_by == client:
            self.paused_by, self.owed = None, 0

    def _put(self, client: str | None) -> None:
        before = self.paused_by
        self._journal.record(lambda: setattr(self, "paused_by", before))
        self.paused_by = client
