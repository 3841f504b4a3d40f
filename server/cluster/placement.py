"""Where a gateway's new scene runs: on the worker holding its lease, else on the least
busy worker with room, which claims the lease (:mod:`.worker_host`).

How busy each worker is comes from asking them all every second, from each worker's
answer to a placement (its count then), and from the placements this gateway has under
way; so scenes placed at the same moment spread instead of all going where there were
fewest a second ago.
"""

from __future__ import annotations

import asyncio
import random
import time
from collections import Counter
from typing import Any

from .bus import PLACE, Bus, Unanswered, attach_subject
from .leases import break_worker, lease_holder

GATHER_SECONDS = 0.2  # how long workers have to say how busy they are
SURVEY_SECONDS = 1.0  # how often they are asked
# a worker not heard of this long is left out (a busy one may miss a survey or two; a
# gone one is left out at once when a placement finds nobody listening)
FORGET_SECONDS = 10.0
ATTACH_SECONDS = 10.0  # a worker's answer to a placement (it starts the scene's process)


class Placement:
    """The workers' loads as this gateway knows them, and placing scenes with them."""

    def __init__(self, bus: Bus) -> None:
        self.bus = bus
        self._loads: dict[str, tuple[int, bool, float]] = {}  # worker -> scenes, room, heard
        self._under_way: Counter[str] = Counter()
        self._surveyed = float("-inf")

    async def place(self, attachment: str, scene: str) -> tuple[str, dict[str, Any]] | None:
        """One try: attach to the lease holder, else to the least busy workers in turn;
        the worker and its answer, or None (try again: a lease lapsing, nobody with room)."""
        holder = await lease_holder(self.bus.workers, self.bus.scenes, scene)
        for worker in [holder] if holder is not None else await self._least_busy():
            self._under_way[worker] += 1
            try:
                answer = await self.bus.request(attach_subject(worker), (attachment, scene),
                                                ATTACH_SECONDS)
            except Unanswered as unanswered:
                if unanswered.gone:  # it has left the bus: its lease need not lapse
                    self._loads.pop(worker, None)
                    await break_worker(self.bus.workers, worker)
                continue  # (if slow, its lease lapses in time)
            finally:
                self._under_way[worker] -= 1
            if answer[0] == "attached":
                self._heard(worker, answer[1]["scenes"], answer[1]["room"])
                return worker, answer[1]
            if answer[0] == "elsewhere":
                return None  # placed meanwhile: its holder, next try
        return None

    async def _least_busy(self) -> list[str]:
        """Workers with room, the least busy first (equals in random order)."""
        if time.monotonic() - self._surveyed > 2 * SURVEY_SECONDS:  # (an answer knows one)
            await self.survey()
        now = time.monotonic()
        loads = {name: scenes + self._under_way[name]
                 for name, (scenes, room, heard) in self._loads.items()
                 if now - heard < FORGET_SECONDS and room}
        ordered = list(loads)
        random.shuffle(ordered)
        return sorted(ordered, key=loads.__getitem__)

    def _heard(self, worker: str, scenes: int, room: bool) -> None:
        self._loads[worker] = (scenes, room, time.monotonic())

    async def survey(self) -> None:
        """Ask every worker how busy it is."""
        answers = await self.bus.gather(PLACE, None, GATHER_SECONDS)
        for name, scenes, room in answers:
            self._heard(name, scenes, room)
        self._surveyed = time.monotonic()

    async def keep_surveying(self) -> None:
        while True:
            await asyncio.sleep(SURVEY_SECONDS)
            await self.survey()
