"""One client's conversation with a scene: checks, permissions, answers, ownership.

Sans-I/O: :meth:`Session.receive` takes the text of one WebSocket message and returns
the answers to send back; the web layer only moves text.
"""

from __future__ import annotations

import logging
import re
from typing import Any

from ..errors import Forbidden, ForeignId, InternalError, VPError
from .messages import LIMITS, PROTOCOL_VERSION, check_client_message, decode
from .operations import Operations
from .physics import ENGINE
from .scene import Scene

log = logging.getLogger(__name__)
ROLES = ("controller", "viewer")


class Session:
    """A connected client: its id (``c7``), its role, and the objects it created."""

    def __init__(self, scene: Scene, client_id: str, role: str = "controller") -> None:
        if role not in ROLES:
            raise ValueError(f"role must be one of {ROLES}, got {role!r}")
        self.scene = scene
        self.client_id = client_id
        self.role = role
        self.operations = Operations(scene, client_id)
        self.owned: list[str] = []
        self._own_id = re.compile(rf"^{re.escape(client_id)}\.[A-Za-z0-9_.:-]+$")

    def hello(self, tick_rate: float) -> dict[str, Any]:
        """The first message a client receives."""
        return {"op": "hello", "protocol": PROTOCOL_VERSION, "client": self.client_id,
                "role": self.role, "scene": self.scene.name, "time": self.scene.time,
                "tickRate": tick_rate, "limits": dict(LIMITS), "engine": ENGINE}

    def receive(self, text: str | bytes) -> list[dict[str, Any]]:
        """Apply every message in one WebSocket text message; the answers, in order."""
        try:
            messages = decode(text)
        except VPError as error:
            return [error.to_wire()]
        answers = (self.handle(message) for message in messages)
        return [answer for answer in answers if answer is not None]

    def handle(self, message: Any) -> dict[str, Any] | None:
        """Apply one message; its answer (None for a fire-and-forget success)."""
        request_id = _request_id(message)
        op = message.get("op") if isinstance(message, dict) else None
        try:
            check_client_message(message)
            self._authorize(message)
            with self.scene.recording() as changes, self.scene.journal.transaction():
                result = self.operations.apply(message)
        except VPError as error:
            return error.to_wire(request_id, op if isinstance(op, str) else None)
        except Exception:  # a bug: the transaction was undone, the client is told
            log.exception("internal error applying %r", message)
            return InternalError("internal server error; nothing was changed").to_wire(
                request_id, op)
        self._own(message)
        if request_id is None:
            return None
        answer: dict[str, Any] = {"op": "ok", "id": request_id}
        if result is not None:
            answer["result"] = result
        delta = self.scene.delta(changes)
        if delta:
            answer["changes"] = delta
        return answer

    def _authorize(self, message: dict[str, Any]) -> None:
        inner = message["ops"] if message["op"] == "batch" else [message]
        for op in inner:
            if self.role == "viewer" and self.operations.mutates(op):
                raise Forbidden(f"a viewer cannot {op['op']}; connect with role=controller",
                                role=self.role)
            if op["op"] == "create" and not self._own_id.match(op["object"]):
                raise ForeignId(f"new ids of this client look like {self.client_id}.<name>, "
                                f"got {op['object']}", object=op["object"])

    def _own(self, message: dict[str, Any]) -> None:
        inner = message["ops"] if message["op"] == "batch" else [message]
        self.owned.extend(op["object"] for op in inner if op["op"] == "create")

    def close(self) -> list[str]:
        """The client left: delete what it created; the ids deleted at the top."""
        self.scene.watches.drop_watcher(self.client_id)
        deleted = []
        for object_id in reversed(self.owned):
            node = self.scene.nodes.get(object_id)
            if node is not None:
                self.scene.delete(node)
                deleted.append(object_id)
        self.owned.clear()
        return deleted


def _request_id(message: Any) -> int | None:
    if isinstance(message, dict):
        request_id = message.get("id")
        if isinstance(request_id, int) and not isinstance(request_id, bool) and request_id >= 0:
            return request_id
    return None
