"""The WebSocket transport: a reader thread feeding the protocol core, and waiting.

All protocol logic is in :class:`~.protocol.ProtocolCore`; this module only moves text
and lets the caller's thread wait for the reader's.
"""

from __future__ import annotations

import threading
import warnings
from typing import Any

from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect as ws_connect

from .errors import ConnectionLost, ServerError, ServerWarning, Timeout
from .protocol import Handler, ProtocolCore

ANSWER_TIMEOUT = 30.0


class Connection:
    """Requests with ids, answered in order; every other message goes to ``on_message``.

    :meth:`settle` waits until every request sent so far is answered, which is what makes
    reads see earlier writes. Errors of requests nobody waits for are raised by the
    caller's next call (:meth:`raise_deferred`), warnings issued in the caller's thread.
    """

    def __init__(self, url: str, on_message: Handler, on_changes: Handler) -> None:
        # entered by hand: the connection outlives this constructor (closed by close())
        self._ws = ws_connect(url, max_size=None, open_timeout=10).__enter__()
        self.core = ProtocolCore(on_message, on_changes)
        self._lock = threading.Condition()
        self._reader = threading.Thread(target=self._read, name="vp-reader", daemon=True)

    @property
    def closed(self) -> str | None:
        """Why the connection closed, or None while it is open."""
        return self.core.closed

    def start(self) -> None:
        """Start reading messages."""
        self._reader.start()

    def close(self) -> None:
        """Close the WebSocket (the server then deletes what this client made)."""
        self._ws.close()
        self._reader.join(timeout=5)

    def send(self, message: dict[str, Any], wait: bool = False) -> Any:
        """Send a request; with ``wait``, block for its answer and return the result."""
        self.raise_deferred()
        with self._lock:
            self._check_open()
            request = self.core.request(message, wait)
        try:
            self._ws.send(request.text)
        except ConnectionClosed as error:
            raise ConnectionLost(f"connection closed: {error}") from None
        if not wait:
            return None
        with self._lock:
            if not self._lock.wait_for(lambda: request.id in self.core.answers or self.closed,
                                       ANSWER_TIMEOUT):
                raise Timeout(f"no answer to {message['op']} within {ANSWER_TIMEOUT} s")
            if request.id not in self.core.answers:
                self._check_open()
            try:  # a ServerError is raised outside the lock, after the answer's warnings
                result, error = self.core.result(request.id), None
            except ServerError as caught:
                result, error = None, caught
        self._warn()
        if error is not None:
            raise error
        return result

    def settle(self, timeout: float = ANSWER_TIMEOUT) -> None:
        """Wait until every request sent so far is answered; raise a kept error."""
        with self._lock:
            if not self._lock.wait_for(lambda: not self.core.unanswered or self.closed, timeout):
                raise Timeout(f"{len(self.core.unanswered)} requests unanswered after {timeout} s")
            if self.core.unanswered:
                self._check_open()
        self.raise_deferred()

    def raise_deferred(self) -> None:
        """Raise the first kept error of a request nobody waited for (after its warnings)."""
        self._warn()
        with self._lock:
            error = self.core.take_deferred()
        if error is not None:
            raise error

    def _warn(self) -> None:
        """Issue the server's warnings received so far, in the caller's thread."""
        with self._lock:
            remarks = self.core.take_warnings()
        for remark in remarks:
            warnings.warn(remark, ServerWarning, stacklevel=4)

    def _check_open(self) -> None:
        if self.closed is not None:
            raise ConnectionLost(self.closed)

    def _read(self) -> None:
        try:
            for text in self._ws:
                with self._lock:
                    self.core.receive(text)
                    self._lock.notify_all()
            reason = "the server closed the connection"
        except ConnectionClosed as error:
            reason = f"connection closed: {error}"
        except Exception as error:  # a broken message must not leave waiters hanging
            reason = f"reading failed: {error!r}"
        with self._lock:
            self.core.lost(reason)
            self._lock.notify_all()
