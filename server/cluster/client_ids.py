"""Client ids and the resume keys' secret, shared by a cluster's gateways through the bus's
``vp_cluster`` bucket, so that a client resumes through any gateway and no two gateways
hand out the same id.

The bucket's ``clients`` key is how far ids have been handed out; a gateway takes a block
of :data:`BLOCK` at a time with compare-and-set (and the next block before this one runs
out, so handing out an id never waits for the bus). ``secret`` is made once, by whichever
gateway comes first.
"""

from __future__ import annotations

import asyncio
import logging
import secrets
from collections import deque

from nats.js.errors import KeyDeletedError, KeyNotFoundError, KeyWrongLastSequenceError
from nats.js.kv import KeyValue

from ..core.kit.errors import LimitExceeded

log = logging.getLogger(__name__)
BLOCK = 1000


async def _get_or_create(shared: KeyValue, key: str, value: bytes) -> tuple[bytes, int]:
    """The key's value and revision, written first as ``value`` when it has none."""
    while True:
        try:
            entry = await shared.get(key)
            return entry.value or b"", entry.revision or 0
        except (KeyNotFoundError, KeyDeletedError):
            try:
                return value, await shared.create(key, value)
            except KeyWrongLastSequenceError:
                continue  # another gateway wrote it first: read theirs


class SharedClientIds:
    """A gateway's :class:`server.web.connections.client_ids.ClientIdSource`."""

    def __init__(self, shared: KeyValue, secret: bytes) -> None:
        self._shared = shared
        self.secret = secret
        self._blocks: deque[tuple[int, int]] = deque()  # [start, end) not handed out yet
        self._floor = 0  # no id up to this one (a document's owners)
        self._refill: asyncio.Task[None] | None = None
        self._raising: asyncio.Task[None] | None = None

    @classmethod
    async def open(cls, shared: KeyValue) -> SharedClientIds:
        """The cluster's secret (made if this gateway is the first) and a first block."""
        secret, _ = await _get_or_create(shared, "secret", secrets.token_hex(32).encode())
        ids = cls(shared, bytes.fromhex(secret.decode()))
        await ids._take_block()
        return ids

    def next(self) -> int:
        while self._blocks:
            start, end = self._blocks[0]
            start = max(start, self._floor + 1)
            if start < end:
                self._blocks[0] = (start + 1, end)
                self._top_up()
                return start
            self._blocks.popleft()
        self._top_up()
        raise LimitExceeded("no client id can be handed out until the bus answers; connect "
                            "again in a moment", limit="clientIdBlock", value=BLOCK)

    def reserve(self, upto: int) -> None:
        self._floor = max(self._floor, upto)
        self._raising = asyncio.create_task(self._raise(upto))

    async def available(self) -> None:
        """Wait until an id can be handed out (the shared count raised past a document's
        owners first, then a block past them taken)."""
        while self._left() <= 0:
            if self._raising is not None:
                await self._raising
            await self._take_block()

    def _left(self) -> int:
        return sum(max(0, end - max(start, self._floor + 1)) for start, end in self._blocks)

    def _top_up(self) -> None:
        if self._left() < BLOCK // 2 and (self._refill is None or self._refill.done()):
            self._refill = asyncio.create_task(self._take_block())

    async def _take_block(self) -> None:
        while True:
            value, revision = await _get_or_create(self._shared, "clients", b"1")
            start = int(value)
            try:
                await self._shared.update("clients", str(start + BLOCK).encode(), last=revision)
            except KeyWrongLastSequenceError:
                continue  # another gateway took one meanwhile
            self._blocks.append((start, start + BLOCK))
            return

    async def _raise(self, upto: int) -> None:
        """The shared count past ``upto``, so no gateway hands out those ids."""
        while True:
            value, revision = await _get_or_create(self._shared, "clients", b"1")
            if int(value) > upto:
                return
            try:
                await self._shared.update("clients", str(upto + 1).encode(), last=revision)
                return
            except KeyWrongLastSequenceError:
                continue
