"""Where a gateway's new scene runs: on the worker holding its lease, else on the least
busy worker with room, which claims the lease (:mod:`.worker_host`).

How busy each worker is (its scenes with a client, or made for one about to join:
WorkerHost.attended) comes from asking them all every second, from each worker's answer
to a placement, from what a worker tells when a client leaves, and from the placements
this gateway has under way; of a worker's loads the one it stamped last counts, whichever
way it came. So scenes placed at the same moment spread instead of all going where there
were fewest a second ago. When every worker on the bus, asked afresh, has no room, the
scene is refused at once (``limit_exceeded``, naming each worker's limit), as a single
server refuses past ``--limit scenes``: waiting would not make room, and the client is
told which flag does.
"""

from __future__ import annotations

import asyncio
import logging
import random
import time
from collections import Counter

from ..core.kit.errors import LimitExceeded
from .bus import PLACE, Bus, ReturnAddress, Unanswered, attach_subject
from .bus_messages import Attach, Attached, Elsewhere, Full, Load
from .leases import break_worker, lease_holder, living_workers

log = logging.getLogger(__name__)
# How long workers have to say how busy they are: a survey ends once every living worker
# (its key in the bus's bucket) has answered, at most SURVEY_WAIT_SECONDS after it asked. A
# fixed 0.2 s missed a worker slow to answer on a loaded machine, and a vector's two scenes
# placed at once both went to the one that had answered. GATHER_SECONDS bounds a survey
# when no worker's key is known (the bucket unread, or the workers just starting).
SURVEY_WAIT_SECONDS = 2.0
GATHER_SECONDS = 0.2
SURVEY_SECONDS = 1.0  # how often they are asked
# a worker not heard of this long is left out (a busy one may miss a survey or two; a
# gone one is left out at once when a placement finds nobody listening)
FORGET_SECONDS = 10.0
ATTACH_SECONDS = 10.0  # a worker's answer to a placement (it starts the scene's process)


class Placement:
    """The workers' loads as this gateway knows them, and placing scenes with them."""

    def __init__(self, bus: Bus) -> None:
        self.bus = bus
        self._loads: dict[str, tuple[Load, float]] = {}  # worker -> its newest, when heard
        self._under_way: Counter[str] = Counter()
        self._surveyed = float("-inf")

    async def place(self, attachment: str, scene: str,
                    expecting: bool = True) -> tuple[str, Attached] | None:
        """One try: attach to the lease holder, else to the least busy workers in turn
        (``expecting``: a client waits for the scene, which counts at once where it goes);
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
                answer = await self.bus.request(attach_subject(worker),
                                                Attach(attachment, scene, expecting),
                                                ATTACH_SECONDS)
            except Unanswered as unanswered:
                if unanswered.gone:  # it has left the bus: its lease need not lapse
                    self._loads.pop(worker, None)
                    await break_worker(self.bus.workers, worker)
                continue  # (if slow, its lease lapses in time)
            finally:
                self._under_way[worker] -= 1
            match answer:
                case Attached(load=load):
                    self._heard(load)
                    return worker, answer
                case Elsewhere():
                    return None  # placed meanwhile: its holder, next try
                case Full(load):  # filled up since it was asked: the next one
                    self._heard(load)
                case _:
                    raise TypeError(f"not an answer to Attach: {answer!r}")
        return None

    async def _least_busy(self) -> list[str]:
        """Workers with room, the least busy first (equals in random order)."""
        if time.monotonic() - self._surveyed > 2 * SURVEY_SECONDS:  # (an answer knows one)
            await self.survey()
        now = time.monotonic()
        loads = {name: load.scenes + self._under_way[name]
                 for name, (load, heard) in self._loads.items()
                 if now - heard < FORGET_SECONDS and load.room is None}
        ordered = list(loads)
        random.shuffle(ordered)
        return sorted(ordered, key=loads.__getitem__)

    def _heard(self, load: Load) -> None:
        known = self._loads.get(load.worker)
        if known is None or known[0].stamp <= load.stamp:
            self._loads[load.worker] = (load, time.monotonic())

    async def told(self, load: Load, reply: ReturnAddress | None) -> None:
        """A worker's load, told as it changed (subscribed to ``LOADS``)."""
        self._heard(load)

    def _refuse(self, scene: str) -> None:
        """Raise the refusal of a scene no worker has room for (none when no worker is
        known: one may be starting, or a dead one's lease lapsing)."""
        now = time.monotonic()
        full = {name: load.room for name, (load, heard) in sorted(self._loads.items())
                if now - heard < FORGET_SECONDS and load.room is not None}
        if not full:
            return
        first = next(iter(full.values()))
        reasons = "; ".join(f"{name}: {reason.text} ({reason.flag})" for name, reason in full.items())
        raise LimitExceeded(f"no worker of the cluster has room for scene {scene}: {reasons}; "
                            f"try again later, or start another worker", limit=first.limit,
                            value=first.value, flag=first.flag, scene=scene)

    async def survey(self) -> None:
        """Ask every worker how busy it is, hearing every living worker's answer (an
        answer older than what a worker said since, to a placement made while the survey
        gathered, does not count: it hid a scene just placed, and a vector's two scenes
        went to one worker)."""
        living = await living_workers(self.bus.workers)

        def everyone(answers: list[Load]) -> bool:
            return living <= {load.worker for load in answers}
        wait = SURVEY_WAIT_SECONDS if living else GATHER_SECONDS
        for load in await self.bus.gather(PLACE, None, wait, everyone if living else None):
            self._heard(load)
        self._surveyed = time.monotonic()

    async def keep_surveying(self) -> None:
        while True:
            await asyncio.sleep(SURVEY_SECONDS)
            if self.bus.link.down_since is None:
                try:
                    await self.survey()
                except Exception as error:  # the bus went away meanwhile: the next one
                    log.warning("surveying the workers: %s", error or type(error).__name__)
