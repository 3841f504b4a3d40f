"""What waits to be sent to one connection."""

from __future__ import annotations

import asyncio
from collections import deque

from .outgoing import Outgoing


class SlowConsumer(Exception):
    """A connection fell so far behind that it is closed rather than buffered forever."""


class Outbox:
    """A queue of messages in order, where a frame behind a waiting frame merges into it.

    Answers, ``added`` and ``removed`` are never dropped; frames are folded, so a slow
    viewer gets the latest state, not a growing backlog. A connection whose waiting
    messages pass ``limit`` bytes is not reading them: it is closed.
    """

    def __init__(self, limit: int = 32 << 20) -> None:
        self._queue: deque[Outgoing] = deque()
        self._ready = asyncio.Event()
        self._limit = limit
        self.bytes = 0
        self.merged = 0

    def __len__(self) -> int:
        return len(self._queue)

    def put(self, item: Outgoing) -> None:
        """Queue a message; raises :class:`SlowConsumer` past the limit."""
        queue = self._queue
        if item.op == "frame" and queue and queue[-1].op == "frame":
            older = queue.pop()
            self.bytes -= len(older.text)
            item = item.behind(older)
            self.merged += 1
        if self.bytes + len(item.text) > self._limit:
            raise SlowConsumer(f"more than {self._limit} bytes waiting to be sent")
        queue.append(item)
        self.bytes += len(item.text)
        self._ready.set()

    async def get(self) -> Outgoing:
        """The next message, waiting for one if needed."""
        while not self._queue:
            self._ready.clear()
            await self._ready.wait()
        item = self._queue.popleft()
        self.bytes -= len(item.text)
        return item
