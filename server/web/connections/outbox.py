"""What waits to be sent to one connection."""

from __future__ import annotations

import asyncio
import json
import weakref
from collections import deque
from typing import Any

from ...core.protocol.messages import encode
from ...core.scene.frames import merge_frames
from .framed_socket import frame_of


class Outgoing:
    """A message's JSON text and op, encoded once however many connections get it.

    Made in a scene's process and sent to the server's as text; framed for the WebSocket
    once, here, when first sent; decoded again only where it is needed (folding frames
    for a slow reader).
    """

    __slots__ = ("op", "text", "_message", "_frame", "_behind", "__weakref__")

    def __init__(self, op: str, text: str, message: dict[str, Any] | None = None) -> None:
        self.op = op
        self.text = text
        self._message = message
        self._frame: bytes | None = None
        # a frame this one was folded behind (weakly: a strong key would chain every frame
        # to the one before, for ever) -> the fold
        self._behind: weakref.WeakKeyDictionary[Outgoing, Outgoing] | None = None

    @classmethod
    def of(cls, message: dict[str, Any]) -> Outgoing:
        return cls(message["op"], encode(message), message)

    @property
    def message(self) -> dict[str, Any]:
        if self._message is None:
            self._message = json.loads(self.text)
        return self._message

    @property
    def frame(self) -> bytes:
        """The message as one WebSocket frame: the same bytes for every connection."""
        if self._frame is None:
            self._frame = frame_of(self.text)
        return self._frame

    def behind(self, older: Outgoing) -> Outgoing:
        """This frame folded behind ``older`` (both frames), made once for every connection
        that has ``older`` waiting: readers that fall behind together (a swamped server,
        its viewers reading slowly) would otherwise each decode, merge and encode the same
        two frames, the more the further behind."""
        if self._behind is None:
            self._behind = weakref.WeakKeyDictionary()
        fold = self._behind.get(older)
        if fold is None:
            fold = self._behind[older] = Outgoing.of(merge_frames(older.message, self.message))
        return fold

    def __reduce__(self) -> tuple[Any, ...]:
        return Outgoing, (self.op, self.text)  # the text travels, not the decoded message


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
