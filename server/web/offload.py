"""Work that must not run in the event loop's process: checking uploads, reading saved files.

Parsing JSON and reading meshes hold the GIL in long C calls (``json.loads`` of 8 MiB takes
~100 ms in one), so a thread would still stall every viewer's frames. Here such work runs in
a process of its own, whose memory is capped: a file that a check missed runs out of room
there (and is refused) instead of taking the server's memory with it.
"""

from __future__ import annotations

import asyncio
import logging
import os
import resource
import signal
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Any, Callable

from ..errors import InternalError, LimitExceeded, TooLarge
from .parent_death import end_with_parent
from .runner import CONTEXT

log = logging.getLogger(__name__)
MEMORY_BYTES = 3 << 30  # address space of the checking process (numpy and trimesh included)


def _start(nice: int) -> None:
    """A checking process: its memory capped, below the scenes' priority by ``nice``, and
    it ends with the server."""
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_BYTES, resource.RLIM_INFINITY))
    if nice:
        os.nice(nice)
    end_with_parent(signal.SIGKILL)  # it keeps nothing that a stop should save


class Offload:
    """One process (started on first use, and again after it died) for one kind of work,
    at a lower priority than the scenes' (``nice``). With a ``limit`` (a name of
    :class:`~server.core.kit.limits.Limits` and its value), at most that many calls run or
    wait at once: the next is refused with ``limit_exceeded`` (HTTP 429) naming it."""

    def __init__(self, limit: tuple[str, int] | None = None, what: str = "jobs",
                 nice: int = 0) -> None:
        self._pool: ProcessPoolExecutor | None = None
        self._limit, self._what, self._nice = limit, what, nice
        self.waiting = 0  # calls running or waiting now

    async def run(self, function: Callable[..., Any], *args: Any) -> Any:
        """``function(*args)`` in the process; its VPErrors are raised here."""
        if self._limit is not None and self.waiting >= self._limit[1]:
            name, value = self._limit
            raise LimitExceeded(f"the server is busy: {value} {self._what} are running or "
                                f"waiting; try again once one is done", limit=name, value=value)
        if self._pool is None:
            self._pool = ProcessPoolExecutor(1, mp_context=CONTEXT, initializer=_start,
                                             initargs=(self._nice,))
        pool = self._pool
        self.waiting += 1
        try:
            return await asyncio.get_running_loop().run_in_executor(pool, function, *args)
        except MemoryError:
            raise TooLarge(f"checking this needs more than the {MEMORY_BYTES >> 30} GiB the "
                           f"server allows; nothing was kept") from None
        except BrokenProcessPool:
            log.error("the checking process ended; it starts again")
            if self._pool is pool:
                self._pool = None
                pool.shutdown(wait=False, cancel_futures=True)
            raise InternalError("the process checking this ended; nothing was kept") from None
        finally:
            self.waiting -= 1

    def close(self) -> None:
        """Stop the checking process."""
        if self._pool is not None:
            self._pool.shutdown(wait=False, cancel_futures=True)
            self._pool = None
