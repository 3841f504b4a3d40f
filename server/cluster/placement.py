"""Where a gateway's new scene runs: on the worker holding its lease, else on the least
busy worker with room, which claims the lease (:mod:`.worker_host`).

How busy each worker is (its scenes with a client, or made for one about to join:
WorkerHost.attended) comes from asking them all every second, from each worker's answer
to a placement (its count then, kept over an older survey's), and from the placements
this gateway has under way; so scenes placed at the same moment spread instead of all
going where there were fewest a second ago. When every worker on the bus, asked afresh,
has no room, the scene is refused at once (``limit_exceeded``, naming each worker's
limit), as a single server refuses past ``--limit scenes``: waiting would not make room,
and the client is told which flag does.
"""

from __future__ import annotations

import asyncio
import logging
import random
import time
from collections import Counter
from typing import Any

from ..errors import LimitExceeded
from .bus import PLACE, Bus, NoRoom, Unanswered, attach_subject
from .leases import break_worker, lease_holder

log = logging.getLogger(__name__)
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
        # worker -> scenes, why it has no room (None: it has), when heard
        self._loads: dict[str, tuple[int, NoRoom | None, float]] = {}
        self._under_way: Counter[str] = Counter()
        self._surveyed = float("-inf")

    async def place(self, attachment: str, scene: str) -> tuple[str, dict[str, Any]] | None:
        """One try: attach to the lease holder, else to the least busy workers in turn;
        the worker and its answer, or None (try again: a lease lapsing, no worker heard
        of). Raises :class:`LimitExceeded` when no worker has room."""
        holder = await lease_holder(self.bus.workers, self.bus.scenes, scene)
        candidates = [holder] if holder is not None else await self._least_busy()
        if not candidates and holder is None:
            if time.monotonic() - self._surveyed > GATHER_SECONDS:  # (_least_busy may have)
                await self.survey()  # fresh word before a refusal: a scene may have just ended
            candidates = await self._least_busy()
            if not candidates:
                self._refuse(scene)
        for worker in candidates:
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
            if answer[0] == "full":  # filled up since it was asked: the next one
                self._heard(worker, self._loads.get(worker, (0,))[0], answer[1])
        return None

    async def _least_busy(self) -> list[str]:
        """Workers with room, the least busy first (equals in random order)."""
        if time.monotonic() - self._surveyed > 2 * SURVEY_SECONDS:  # (an answer knows one)
            await self.survey()
        now = time.monotonic()
        loads = {name: scenes + self._under_way[name]
                 for name, (scenes, full, heard) in self._loads.items()
                 if now - heard < FORGET_SECONDS and full is None}
        ordered = list(loads)
        random.shuffle(ordered)
        return sorted(ordered, key=loads.__getitem__)

    def _heard(self, worker: str, scenes: int, full: NoRoom | None) -> None:
        self._loads[worker] = (scenes, full, time.monotonic())

    def _refuse(self, scene: str) -> None:
        """Raise the refusal of a scene no worker has room for (none when no worker is
        known: one may be starting, or a dead one's lease lapsing)."""
        now = time.monotonic()
        full = {name: reason for name, (_, reason, heard) in sorted(self._loads.items())
                if now - heard < FORGET_SECONDS and reason is not None}
        if not full:
            return
        first = next(iter(full.values()))
        reasons = "; ".join(f"{name}: {reason.text} ({reason.flag})" for name, reason in full.items())
        raise LimitExceeded(f"no worker of the cluster has room for scene {scene}: {reasons}; "
                            f"try again later, or start another worker", limit=first.limit,
                            value=first.value, flag=first.flag, scene=scene)

    async def survey(self) -> None:
        """Ask every worker how busy it is. A worker's answer to a placement made while the
        survey gathered is newer than its answer to the survey, and stays (the survey's
        hid a scene just placed: a vector's two scenes went to one worker)."""
        asked = time.monotonic()
        answers = await self.bus.gather(PLACE, None, GATHER_SECONDS)
        for name, scenes, full in answers:
            if self._loads.get(name, (0, None, float("-inf")))[2] < asked:
                self._heard(name, scenes, full)
        self._surveyed = time.monotonic()

    async def keep_surveying(self) -> None:
        while True:
            await asyncio.sleep(SURVEY_SECONDS)
            if self.bus.link.down_since is None:
                try:
                    await self.survey()
                except Exception as error:  # the bus went away meanwhile: the next one
                    log.warning("surveying the workers: %s", error or type(error).__name__)
