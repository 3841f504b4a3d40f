"""The client ids a server hands out (c1, c2, …) and the key its resume keys are signed
with: :class:`ClientIds` for one server (kept in its state folder, if it has one); a
cluster's gateways share theirs through the bus (:mod:`server.cluster.client_ids`)."""

from __future__ import annotations

import secrets
from typing import Protocol

from ..storage.state_dir import StateDir


class ClientIdSource(Protocol):
    """What :class:`server.web.scenes.hub.Hubs` needs: fresh numbers, never handed out twice."""

    secret: bytes  # signs resume keys

    def next(self) -> int:
        """A client number never handed out before."""

    def reserve(self, upto: int) -> None:
        """Never hand out numbers up to ``upto`` (owners a document brought in)."""

    async def available(self) -> None:
        """Wait until :meth:`next` can answer at once."""


class ClientIds:
    """One server's ids: counted from 1, or with a state folder from past the ids it noted
    there (:meth:`StateDir.reserve_clients`), so a restart never hands one out twice."""

    def __init__(self, state: StateDir | None = None) -> None:
        self._state = state
        self.secret = state.secret if state is not None else secrets.token_bytes(32)
        self._last = state.clients_reserved if state is not None else 0
        self._reserved = self._last
        self._note(self._last)

    def next(self) -> int:
        self._last += 1
        self._note(self._last)
        return self._last

    def reserve(self, upto: int) -> None:
        self._last = max(self._last, upto)
        self._note(self._last)

    async def available(self) -> None:
        """Always: ids are counted here."""

    def _note(self, upto: int) -> None:
        if self._state is not None and upto >= self._reserved:
            self._reserved = self._state.reserve_clients(upto)
