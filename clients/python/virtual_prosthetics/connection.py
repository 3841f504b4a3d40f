"""The WebSocket to the server: sends requests, reads answers and frames on a thread."""

from __future__ import annotations

import json
import math
import threading
import warnings
from itertools import count
from typing import Any, Callable

from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect as ws_connect

from .errors import ConnectionLost, ServerError, ServerWarning, Timeout

Handler = Callable[[dict[str, Any]], None]
ANSWER_TIMEOUT = 30.0


def _non_finite(name: str) -> float:
    return {"Infinity": math.inf, "-Infinity": -math.inf, "NaN": math.nan}[name]


class _Waiter:
    """An answer someone is waiting for."""

    def __init__(self) -> None:
        self.done = threading.Event()
        self.answer: dict[str, Any] | None = None


class Connection:
    """Requests with ids, answered in order; every other message goes to ``on_message``.

    Each request gets an id, so the connection always knows how many are unanswered:
    :meth:`settle` waits until none are, which is what makes reads see earlier writes.
    Errors of requests nobody waits for are kept and raised by :meth:`raise_deferred`.
    """

    def __init__(self, url: str, on_message: Handler, on_answer: Handler) -> None:
        # entered by hand: the connection outlives this constructor (closed by close())
        self._ws = ws_connect(url, max_size=None, open_timeout=10).__enter__()
        self._on_message = on_message
        self._on_answer = on_answer
        self._ids = count(1)
        self._lock = threading.Condition()
        self._unanswered: set[int] = set()
        self._waiters: dict[int, _Waiter] = {}
        self._deferred: list[ServerError] = []
        self._remarks: list[str] = []  # warnings in answers, not yet issued
        self.closed: str | None = None
        self._reader = threading.Thread(target=self._read, name="vp-reader", daemon=True)

    def start(self) -> None:
        """Start reading messages."""
        self._reader.start()

    def close(self) -> None:
        """Close the WebSocket (the server then deletes what this client made)."""
        self._ws.close()
        self._reader.join(timeout=5)

    # --- sending -------------------------------------------------------------------------

    def send(self, message: dict[str, Any], wait: bool = False) -> Any:
        """Send a request; with ``wait``, block for its answer and return the result."""
        self.raise_deferred()
        request_id = next(self._ids)
        waiter = _Waiter() if wait else None
        with self._lock:
            self._check_open()
            self._unanswered.add(request_id)
            if waiter is not None:
                self._waiters[request_id] = waiter
        try:
            self._ws.send(json.dumps({**message, "id": request_id}, allow_nan=False))
        except ConnectionClosed as error:
            raise ConnectionLost(f"connection closed: {error}") from None
        if waiter is None:
            return None
        if not waiter.done.wait(ANSWER_TIMEOUT) or waiter.answer is None:
            self._check_open()
            raise Timeout(f"no answer to {message['op']} within {ANSWER_TIMEOUT} s")
        if waiter.answer["op"] == "error":
            raise ServerError.from_wire(waiter.answer)
        self._warn()
        return waiter.answer.get("result")

    def settle(self, timeout: float = ANSWER_TIMEOUT) -> None:
        """Wait until every request sent so far is answered; raise a kept error."""
        with self._lock:
            if not self._lock.wait_for(lambda: not self._unanswered or self.closed, timeout):
                raise Timeout(f"{len(self._unanswered)} requests unanswered after {timeout} s")
            if self._unanswered:
                self._check_open()
        self.raise_deferred()

    def raise_deferred(self) -> None:
        """Raise the first kept error of a request nobody waited for (after its warnings)."""
        self._warn()
        with self._lock:
            if self._deferred:
                error = self._deferred.pop(0)
                raise error

    def _warn(self) -> None:
        """Issue the server's warnings received so far, in the caller's thread."""
        with self._lock:
            remarks, self._remarks = self._remarks, []
        for remark in remarks:
            warnings.warn(remark, ServerWarning, stacklevel=4)

    def _check_open(self) -> None:
        if self.closed is not None:
            raise ConnectionLost(self.closed)

    # --- receiving -----------------------------------------------------------------------

    def _read(self) -> None:
        try:
            for text in self._ws:
                self._dispatch(json.loads(text, parse_constant=_non_finite))
            reason = "the server closed the connection"
        except ConnectionClosed as error:
            reason = f"connection closed: {error}"
        except Exception as error:  # a broken message must not leave waiters hanging
            reason = f"reading failed: {error!r}"
        with self._lock:
            self.closed = reason
            for waiter in self._waiters.values():
                waiter.done.set()
            self._lock.notify_all()

    def _dispatch(self, message: dict[str, Any]) -> None:
        request_id = message.get("id")
        if message["op"] not in ("ok", "error") or request_id is None:
            if message["op"] == "error":
                with self._lock:
                    self._deferred.append(ServerError.from_wire(message))
            self._on_message(message)
            return
        self._on_answer(message)
        with self._lock:
            self._remarks += message.get("warnings", [])
            self._unanswered.discard(request_id)
            waiter = self._waiters.pop(request_id, None)
            if waiter is not None:
                waiter.answer = message
                waiter.done.set()
            elif message["op"] == "error":
                self._deferred.append(ServerError.from_wire(message))
            self._lock.notify_all()
