"""One client's conversation with a scene: checks, permissions, answers, ownership.

Sans-I/O: :meth:`Session.receive` takes the text of one WebSocket message and returns
the answers to send back; the web layer only moves text.
"""

from __future__ import annotations

import logging
import re
import time
from typing import Any, Callable

from ..kit.errors import Forbidden, ForeignId, InternalError, LimitExceeded, VPError
from ..kit.rates import TokenBucket
from ..kit.wire_messages import Hello, Ok
from ..physics.engine import ENGINE
from ..physics.settings import Physics
from ..scene.scene import Scene
from . import api
from .messages import (PROTOCOL_VERSION, byte_size, check_client_message, decode, encode,
                       request_id)
from .operations import Operations

log = logging.getLogger(__name__)
ROLES = ("controller", "viewer")


class Session:
    """A connected client: its id (``c7``), its role, and the objects it created."""

    def __init__(self, scene: Scene, client_id: str, role: str = "controller",
                 resume: str | None = None, trusted: bool = False) -> None:
        if role not in ROLES:
            raise ValueError(f"role must be one of {ROLES}, got {role!r}")
        self.scene = scene
        self.client_id = client_id
        self.role = role
        self.operations = Operations(scene, client_id, trusted)
        self.resume = resume  # what a reconnecting client sends to be this client again
        # told of every request that changed the scene, once it is applied (the journal)
        self.on_change: Callable[[Session, dict[str, Any]], None] | None = None
        # takes the ticks a step asked for (the process serving the scene): what follows a
        # step in the same text sees the world it stepped to, so a script steps and reads
        # in one message
        self.on_step: Callable[[], None] | None = None
        now = time.monotonic()
        self._bytes = TokenBucket(scene.limits.bytes_per_second, now)
        self._own_id = re.compile(rf"{re.escape(client_id)}\.[A-Za-z0-9_.:-]+")

    def hello(self, tick_rate: float) -> Hello:
        """The first message a client receives."""
        hello = Hello(op="hello", protocol=PROTOCOL_VERSION, client=self.client_id,
                      role=self.role, scene=self.scene.name, time=self.scene.time,
                      tickRate=tick_rate, limits=self.scene.limits.wire(), engine=ENGINE,
                      slots=api.slot_counts(), physics=Physics().wire())
        if self.resume:
            hello["resume"] = self.resume
        return hello

    def receive(self, text: str | bytes, now: float | None = None) -> list[dict[str, Any]]:
        """Apply every message in one WebSocket text message; the answers, in order.

        ``now`` (monotonic seconds) keeps the connection's byte rate (``bytesPerSecond``,
        against floods of text that fails before it does anything); a text over it is
        answered with ``limit_exceeded`` for each request in it, and nothing is applied.
        Requests are not counted: a client sending faster than its scene applies is slowed
        by the web layer, which stops reading its socket (server.web.http.socket).
        """
        return [answer for answer, _ in self.receive_encoded(text, now)]

    def receive_encoded(self, text: str | bytes,
                        now: float | None = None) -> list[tuple[dict[str, Any], str]]:
        """:meth:`receive`, each answer with its JSON text (encoded once, here)."""
        now = time.monotonic() if now is None else now
        try:
            messages = decode(text, self.scene.limits)
        except VPError as error:
            return [_encoded(error.to_wire())]
        refusal = self._over_rate(text, now)
        if refusal is not None:
            return [_encoded(refusal.to_wire(request_id(m), _op_name(m))) for m in messages]
        answers = []
        for message in messages:
            answer = self._handle(message)
            if answer is not None:
                answers.append(answer)
            if self.on_step is not None and self.scene.clock.owed:
                self.on_step()
        return answers

    def _over_rate(self, text: str | bytes, now: float) -> VPError | None:
        limits = self.scene.limits
        if not self._bytes.take(byte_size(text), now):
            return LimitExceeded(f"more than {limits.bytes_per_second} bytes a second from "
                                 f"this connection; slow down", limit="bytesPerSecond",
                                 value=limits.bytes_per_second)
        return None

    def handle(self, message: Any) -> dict[str, Any] | None:
        """Apply one message; its answer (None for a fire-and-forget success)."""
        answer = self._handle(message)
        return None if answer is None else answer[0]

    def _handle(self, message: Any) -> tuple[dict[str, Any], str] | None:
        answer_id, op = request_id(message), _op_name(message)
        try:
            check_client_message(message)
            self._authorize(message)
            with self.scene.recording() as changes, self.scene.journal.transaction():
                result = self.operations.apply(message)
                self.scene.bodies.check_trees()  # inside: a tree too large undoes the request
                answer = self._answer(answer_id, result, changes)
            if changes and self.on_change is not None:
                self.on_change(self, message)
            return answer
        except VPError as error:
            return _encoded(error.to_wire(answer_id, op))
        except Exception:  # a bug: the transaction was undone, the client is told
            log.exception("internal error applying a %s request of %s", op, self.client_id)
            return _encoded(InternalError("internal server error; nothing was changed")
                            .to_wire(answer_id, op))

    def _answer(self, answer_id: int | None, result: Any,
                changes: Any) -> tuple[dict[str, Any], str] | None:
        """The ok answer and its text; encoding inside the transaction means a value JSON
        cannot carry undoes the request."""
        if answer_id is None:
            return None
        answer = Ok(op="ok", id=answer_id)
        if result is not None:
            answer["result"] = result
        delta = self.scene.delta(changes)
        if delta:
            answer["changes"] = delta
        if changes.warnings:
            answer["warnings"] = changes.warnings
        return _encoded(answer)

    def _authorize(self, message: dict[str, Any]) -> None:
        inner = message["ops"] if message["op"] == "batch" else [message]
        for op in inner:
            if self.role == "viewer" and self.operations.mutates(op):
                raise Forbidden(f"a viewer cannot {op['op']}; connect with role=controller",
                                role=self.role)
            if op["op"] == "create" and not self._own_id.fullmatch(op["object"]):
                raise ForeignId(f"new ids of this client look like {self.client_id}.<name>, "
                                f"got {op['object']}", object=op["object"])

    def close(self) -> list[str]:
        """The client left: what it created goes (:meth:`Scene.remove_client`); the ids
        deleted at the top."""
        return self.scene.remove_client(self.client_id)


def _encoded(answer: dict[str, Any]) -> tuple[dict[str, Any], str]:
    return answer, encode(answer)


def _op_name(message: Any) -> str | None:
    """The op a message names, when it is one of the protocol's (echoed in errors)."""
    op = message.get("op") if isinstance(message, dict) else None
    return op if isinstance(op, str) and len(op) <= 16 and op.isidentifier() else None
