"""How many new trees a tick builds: a big batch becomes bodies over several ticks.

Bullet's multibody solver grows its arrays one contact row at a time, each growth a copy of
the whole array (:mod:`server.core.physics.clearance`), so the first step after k parts
appear among n costs about k·n: 300 boxes made as a tower in one batch took one step of
440 ms, and 2 000 balls took a tick of 1.5 s to build (0.8 ms a ball, before any step). So
a tick builds new trees (roots that have no body yet), in the order they were made, while
their parts times the world's parts stays within STAGE; the rest wait for the next tick
(at least one tree a tick, however big). A request that reads the physics between ticks
(contacts, sensors, exact touching) builds everything first, as before.

Counted, not timed, so that a script gives the same world on any machine and at any load:
recordings resimulate and tasks repeat byte for byte.
"""

from __future__ import annotations

from contextlib import contextmanager
from typing import Iterator

STAGE = 12_000  # parts made × parts in the world, a tick: a first step of ~100 ms here


class BuildStages:
    """What is left of this tick's stage (None outside a tick: build everything)."""

    def __init__(self) -> None:
        self.left: int | None = None

    @contextmanager
    def tick(self) -> Iterator[None]:
        """Within a tick: new trees are built only as far as STAGE allows."""
        self.left = STAGE
        try:
            yield
        finally:
            self.left = None

    def admits(self, parts: int, world: int) -> bool:
        """Whether a new tree of ``parts`` parts may be built now, in a world of ``world``
        parts (taken from the stage if so). Once one waits, every later one waits too:
        trees are built in the order they were made, which Bullet's solver follows."""
        if self.left is None or not parts:
            return True
        cost = parts * (world + parts)
        if cost > self.left and self.left < STAGE:
            self.left = 0
            return False
        self.left = max(0, self.left - cost)
        return True
