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
from typing import Any, Awaitable, Callable, Protocol

from ...core.kit.errors import InternalError, LimitExceeded, TooLarge, VPError
from ..process.parent_death import end_with_parent
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


class CallerGone(Exception):
    """The caller hung up before its work was done: the work was stopped."""


HangUp = Callable[[], Awaitable[Any]]  # returns once the caller has hung up
HANG_UP_SECONDS = 0.25  # how often a waiting caller's connection is looked at


class Disconnectable(Protocol):
    """A caller whose connection can be asked about (Starlette's ``Request``)."""

    async def is_disconnected(self) -> bool: ...


def hang_up_of(caller: Disconnectable) -> HangUp:
    """What :meth:`Offload.run` waits on to drop the call of a ``caller`` that hung up."""
    async def hung_up() -> None:
        while not await caller.is_disconnected():
            await asyncio.sleep(HANG_UP_SECONDS)
    return hung_up


class Offload:
    """One process (started on first use, and again after it died) for one kind of work,
    at a lower priority than the scenes' (``nice``); with ``per_call``, a process for each
    call instead, ended when its caller hangs up (long work: a resimulation). With a
    ``limit`` (a name of :class:`~server.core.kit.limits.Limits` and its value), at most
    that many calls run or wait at once: the next is refused with ``limit_exceeded`` (HTTP
    429) naming it."""

    def __init__(self, limit: tuple[str, int] | None = None, what: str = "jobs",
                 nice: int = 0, per_call: bool = False) -> None:
        self._pool: ProcessPoolExecutor | None = None
        self._limit, self._what, self._nice = limit, what, nice
        self._per_call = per_call
        self.waiting = 0  # calls running or waiting now

    async def run(self, function: Callable[..., Any], *args: Any,
                  hung_up: HangUp | None = None) -> Any:
        """``function(*args)`` in the process; its VPErrors are raised here. Once
        ``hung_up()`` returns, the call is dropped (:class:`CallerGone`): if it waits, it
        never starts; if it runs in a process of its own, that process is ended."""
        if self._limit is not None and self.waiting >= self._limit[1]:
            name, value = self._limit
            raise LimitExceeded(f"the server is busy: {value} {self._what} are running or "
                                f"waiting; try again once one is done", limit=name, value=value)
        self.waiting += 1
        try:
            if self._per_call:
                return await self._own_process(function, args, hung_up)
            return await _unless(self._pooled(function, args), hung_up)
        finally:
            self.waiting -= 1

    async def _own_process(self, function: Callable[..., Any], args: tuple[Any, ...],
                           hung_up: HangUp | None) -> Any:
        mine, theirs = CONTEXT.Pipe(duplex=False)
        process = CONTEXT.Process(target=_call, args=(theirs, self._nice, function, args),
                                  daemon=True)
        process.start()
        theirs.close()
        try:
            done, value = await _unless(asyncio.to_thread(_answer, mine), hung_up)
        finally:
            if process.is_alive():
                process.kill()  # (its caller has gone: nothing it made is wanted)
            await asyncio.to_thread(process.join, 10)
        mine.close()  # (when dropped, the thread reading it sees its end and lets it go)
        if done:
            return value
        raise value

    async def _pooled(self, function: Callable[..., Any], args: tuple[Any, ...]) -> Any:
        if self._pool is None:
            self._pool = ProcessPoolExecutor(1, mp_context=CONTEXT, initializer=_start,
                                             initargs=(self._nice,))
        pool = self._pool
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

    def close(self) -> None:
        """Stop the checking process."""
        if self._pool is not None:
            self._pool.shutdown(wait=False, cancel_futures=True)
            self._pool = None


async def _unless(work: Awaitable[Any], hung_up: HangUp | None) -> Any:
    """``work``'s outcome, or :class:`CallerGone` (``work`` cancelled) once ``hung_up()``
    returns first."""
    if hung_up is None:
        return await work
    doing, watching = asyncio.ensure_future(work), asyncio.ensure_future(hung_up())
    try:
        await asyncio.wait({doing, watching}, return_when=asyncio.FIRST_COMPLETED)
    finally:
        watching.cancel()
    if not doing.done():
        doing.cancel()
        raise CallerGone("the caller hung up; its work was dropped")
    return doing.result()


def _call(pipe: Any, nice: int, function: Callable[..., Any], args: tuple[Any, ...]) -> None:
    """A process of one call: its outcome goes back through ``pipe`` (errors as values)."""
    _start(nice)
    try:
        outcome: tuple[bool, Any] = (True, function(*args))
    except MemoryError:
        outcome = (False, TooLarge(f"this needs more than the {MEMORY_BYTES >> 30} GiB the "
                                   f"server allows; nothing was kept"))
    except VPError as error:
        outcome = (False, error)
    except Exception:  # a bug: its traceback is in this process's log
        log.exception("offloaded %s failed", getattr(function, "__name__", function))
        outcome = (False, InternalError("internal server error"))
    pipe.send(outcome)


def _answer(pipe: Any) -> tuple[bool, Any]:
    """What a call's process sent back (its end without a word: an internal error)."""
    try:
        return pipe.recv()  # type: ignore[no-any-return]
    except EOFError:
        return False, InternalError("the process doing this ended; nothing was kept")
