"""The client's side of the protocol without any socket or thread (sans-I/O).

Request ids, the answers someone waits for, errors of requests nobody waits for (kept
until the caller's next call), warnings, and which server message goes where. The
threaded transport (:mod:`.connection`) feeds it text and sends what it returns; tests
drive it directly.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

from .codec import decode, encode
from .errors import ConnectionLost, ProtocolError, ServerError
from .wire_messages import SERVER_MESSAGES

Handler = Callable[[dict[str, Any]], None]
SERVER_OPS = frozenset(SERVER_MESSAGES)
ID_ROOM = 24  # bytes: ',"id":' and the largest id


@dataclass(frozen=True)
class Request:
    """A request ready to send: its id and its text."""

    id: int
    text: str


class ProtocolCore:
    """What the client knows of the conversation with the server.

    ``on_message`` gets every server message that is not an answer (hello, snapshot,
    frames, added, removed, errors without id); ``on_changes`` what an ``ok`` answer
    says its request changed.
    """

    def __init__(self, on_message: Handler, on_changes: Handler) -> None:
        self.on_message = on_message
        self.on_changes = on_changes
        self._next_id = 1
        self.unanswered: set[int] = set()
        self._waited: set[int] = set()
        self.answers: dict[int, dict[str, Any]] = {}  # answers of waited requests
        self.deferred: list[Exception] = []
        self.warnings: list[str] = []
        self.closed: str | None = None
        self.resume: str | None = None  # hello's key for connecting again as this client
        self.grace = 0.0  # how long the server keeps this client's objects after a loss
        self.interrupted: set[int] = set()  # waited requests a lost connection left unanswered
        self.message_bytes = 1 << 20  # the server's messageBytes (hello's limits say)

    def request(self, message: dict[str, Any], wait: bool = False) -> Request:
        """The request for ``message`` with a fresh id (``wait``: keep its answer)."""
        request_id, self._next_id = self._next_id, self._next_id + 1
        self.unanswered.add(request_id)
        if wait:
            self._waited.add(request_id)
        return Request(request_id, encode({**message, "id": request_id}))

    def check_size(self, message: dict[str, Any]) -> int:
        """The bytes of a request's text (with room for its id); refused here, as the
        server would, when over the server's ``messageBytes``: the server cannot tell which
        request such a text held, so its refusal would answer none, and the caller would
        wait in vain."""
        # (the codec writes ASCII, escaping the rest: a character is a byte)
        size, limit = len(encode(message)) + ID_ROOM, self.message_bytes
        if size > limit:
            op = message.get("op")
            raise ServerError("too_large", f"a {op} request of {size} bytes is over the "
                              f"server's limit of {limit} bytes (limit messageBytes; vp-server "
                              f"--limit messageBytes=N changes it)", op,
                              {"limit": "messageBytes", "value": limit,
                               "flag": "--limit messageBytes=N"})
        return size

    def receive(self, text: str | bytes) -> dict[str, Any]:
        """Take one text from the server; unknown or malformed messages raise ProtocolError."""
        try:
            message = decode(text)
        except ValueError:
            raise ProtocolError(f"the server sent text that is not JSON: {text[:80]!r}") from None
        if not isinstance(message, dict) or message.get("op") not in SERVER_OPS:
            raise ProtocolError(f"the server sent an unknown message: {str(text)[:80]}")
        if message["op"] in ("ok", "error") and message.get("id") is not None:
            self._answered(message)
        elif message["op"] == "warning":  # the scene's, not a request's: issued the same way
            self.warnings.append(f"scene {message['code']}: {message['message']}")
        else:
            if message["op"] == "hello":
                self.resume = message.get("resume")
                self.grace = float(message.get("limits", {}).get("leaveGraceSeconds", 0))
                self.message_bytes = int(message.get("limits", {}).get("messageBytes", 1 << 20))
            if message["op"] == "error":
                self.deferred.append(ServerError.from_wire(message))
            self.on_message(message)
        return message

    def _answered(self, message: dict[str, Any]) -> None:
        request_id = message["id"]
        if "changes" in message:
            self.on_changes(message["changes"])
        self.warnings += message.get("warnings", [])
        self.unanswered.discard(request_id)
        if request_id in self._waited:
            self._waited.discard(request_id)
            self.answers[request_id] = message
        elif message["op"] == "error":
            self.deferred.append(ServerError.from_wire(message))

    def result(self, request_id: int) -> Any:
        """The result of a waited request's answer (raises its ServerError); KeyError
        while it has not come."""
        answer = self.answers.pop(request_id)
        if answer["op"] == "error":
            raise ServerError.from_wire(answer)
        return answer.get("result")

    def take_deferred(self) -> ServerError | None:
        """The first kept error of a request nobody waited for, if any."""
        return self.deferred.pop(0) if self.deferred else None

    def take_warnings(self) -> list[str]:
        """The server's remarks received so far, once each."""
        remarks, self.warnings = self.warnings, []
        return remarks

    def lost(self, reason: str) -> None:
        """The connection is gone: nothing more will be answered."""
        self.closed = reason

    def reconnected(self) -> None:
        """A new connection replaced a lost one (as the same client): requests sent before
        the loss and not answered may or may not have been applied; who waits for one
        is told so, the others' loss is raised by the next call."""
        lost = ConnectionLost("the connection dropped before a request was answered (it "
                              "may or may not have been applied); reconnected")
        self.interrupted |= self.unanswered & self._waited
        if self.unanswered - self._waited:
            self.deferred.append(lost)
        self._waited -= self.unanswered
        self.unanswered.clear()
