"""The WebSocket transport: a reader thread feeding the protocol core, and waiting.

All protocol logic is in :class:`~.protocol.ProtocolCore`; this module only moves text
and lets the caller's thread wait for the reader's.
"""

from __future__ import annotations

import contextlib
import threading
import time
import warnings
from typing import Any, Iterator
from urllib.parse import parse_qsl, urlencode, urlsplit, urlunsplit

from websockets.exceptions import ConnectionClosed, InvalidHandshake, InvalidStatus, InvalidURI
from websockets.sync.client import connect as ws_connect

from .errors import ConnectionLost, ServerError, ServerWarning, Timeout
from .protocol import Handler, ProtocolCore, Request
from .waiting import bound
from .wire_messages import Batch

RETRY_FIRST, RETRY_MAX = 0.1, 1.0  # seconds between attempts to connect again
REPLACED = 4001  # close code: this client connected again elsewhere (no coming back here)
TEXT_BYTES = 512 * 1024  # gathered requests per text at most (as the JS client): well under
TEXT_MESSAGES = 1_000    # the server's messageBytes (1 MiB) and messagesPerText (10 000)


class Connection:
    """Requests with ids, answered in order; every other message goes to ``on_message``.

    :meth:`settle` waits until every request sent so far is answered, which is what makes
    reads see earlier writes. Errors of requests nobody waits for are raised by the
    caller's next call (:meth:`raise_deferred`), warnings issued in the caller's thread.
    ``timeout``: seconds to wait for the handshake and for answers (:mod:`.waiting`).
    """

    def __init__(self, url: str, on_message: Handler, on_changes: Handler,
                 timeout: float) -> None:
        self._url = url
        self.timeout = timeout
        self._closing = False
        self._reconnecting = False
        self._generation = 0  # connections made so far after the first
        self._ws = _first_open(url, timeout)
        self.core = ProtocolCore(on_message, on_changes)
        self._lock = threading.Condition()
        self._reader = threading.Thread(target=self._read, name="vp-reader", daemon=True)
        self._gathering = 0  # depth of gathering(): requests then wait in _held
        self._held: list[tuple[dict[str, Any], int]] = []  # (request, its text's bytes)

    @property
    def closed(self) -> str | None:
        """Why the connection closed, or None while it is open."""
        return self.core.closed

    def start(self) -> None:
        """Start reading messages."""
        self._reader.start()

    def close(self) -> None:
        """Close the WebSocket (the server then deletes what this client made)."""
        if self._held and self.closed is None:
            self.flush()
        self._closing = True
        self._ws.close()
        self._reader.join(timeout=5)

    @contextlib.contextmanager
    def gathering(self) -> Iterator[None]:
        """Requests sent inside that nobody waits for leave together, as one ``batch``,
        when it ends (or earlier, with the first request someone waits for): an animation
        step's setters reach the server as one request, applied as one (a refused one
        undoes the others; the next call raises it) and answered once, as the JS client
        sends an animation step's."""
        self._gathering += 1
        try:
            yield
        finally:
            self._gathering -= 1
            if not self._gathering and self._held and self.closed is None:
                self.flush()

    def flush(self) -> None:
        """Send the requests :meth:`gathering` holds."""
        held, self._held = self._held, []
        if held:
            self._send(_batches(held), False)

    def send(self, message: dict[str, Any], wait: bool = False) -> Any:
        """Send a request; with ``wait``, block for its answer and return the result."""
        self.raise_deferred()
        size = self.core.check_size(message)
        if self._gathering and not wait:
            self._held.append((message, size))
            return None
        held, self._held = self._held, []
        request = self._send([*_batches(held), message], wait)
        if not wait:
            return None
        with self._lock:
            if not self._lock.wait_for(lambda: request.id in self.core.answers or self.closed
                                       or request.id in self.core.interrupted,
                                       bound(self.timeout)):
                raise Timeout(f"no answer to {message['op']}", self.timeout)
            if request.id in self.core.interrupted:
                self.core.interrupted.discard(request.id)
                raise ConnectionLost(f"the connection dropped before {message['op']} was "
                                     f"answered (it may or may not have been applied)")
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

    def _send(self, messages: list[dict[str, Any]], wait: bool) -> Request:
        """Send requests in as few texts as fit, waiting out a reconnection: requests the
        loss kept from going go again, with new ids, on the new connection. The last
        one's request (``wait``: its answer is kept)."""
        for attempt in range(2):
            with self._lock:
                self._lock.wait_for(lambda: not self._reconnecting, self.core.grace + 10)
                self._check_open()
                last = len(messages) - 1
                requests = [self.core.request(m, wait and k == last) for k, m in enumerate(messages)]
                generation = self._generation
            try:
                for text in _texts(requests):
                    self._ws.send(text)
                return requests[-1]
            except ConnectionClosed as error:
                with self._lock:  # the reader finds the loss too and connects again
                    self._lock.wait_for(lambda: self._generation != generation or
                                        bool(self.closed), self.core.grace + 10)
                    self.core.interrupted.difference_update(r.id for r in requests)
                    if self._generation == generation or attempt:
                        raise ConnectionLost(f"connection closed: {error}") from None
        raise AssertionError("unreachable")

    def settle(self) -> None:
        """Wait until every request sent so far is answered; raise a kept error."""
        if self._held:
            self.flush()
        with self._lock:
            if not self._lock.wait_for(lambda: not self.core.unanswered or self.closed,
                                       bound(self.timeout)):
                raise Timeout(f"no answer to {len(self.core.unanswered)} requests",
                              self.timeout)
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
        while True:
            reason = self._read_until_closed()
            with self._lock:
                self._reconnecting = not self._closing and self.core.resume is not None \
                    and self._ws.close_code != REPLACED
            if not self._reconnecting or not self._reconnect():
                break
        with self._lock:
            self.core.lost(reason)
            self._reconnecting = False
            self._lock.notify_all()

    def _read_until_closed(self) -> str:
        try:
            for text in self._ws:
                with self._lock:
                    self.core.receive(text)
                    self._lock.notify_all()
            return "the server closed the connection"
        except ConnectionClosed as error:
            if error.rcvd is not None and error.rcvd.code == REPLACED:
                return error.rcvd.reason  # the server says why: another connection took over
            return f"connection closed: {error}"
        except Exception as error:  # a broken message must not leave waiters hanging
            return f"reading failed: {error!r}"

    def _reconnect(self) -> bool:
        """Connect again as the same client while the server still keeps its objects; the
        server then sends a fresh hello and snapshot, which resync the mirror."""
        if self.core.resume is None:
            return False
        deadline, pause = time.monotonic() + self.core.grace, RETRY_FIRST
        url = _with_query(self._url, resume=self.core.resume)
        while time.monotonic() < deadline and not self._closing:
            try:
                socket = _open(url, min(self.timeout, 5.0))
            except (OSError, InvalidHandshake, TimeoutError, ConnectionClosed):
                # a server going down (or still starting) may drop us mid-handshake
                time.sleep(min(pause, max(0.0, deadline - time.monotonic())))
                pause = min(RETRY_MAX, pause * 2)
                continue
            with self._lock:
                self._ws = socket
                self.core.reconnected()
                self._generation += 1
                self._reconnecting = False
                self._lock.notify_all()
            return True
        return False


def _first_open(url: str, timeout: float) -> Any:
    """The first connection: a refusal or a wrong address as the client's own errors,
    naming the address without its query (the token)."""
    address = urlunsplit(urlsplit(url)._replace(query=""))
    try:
        return _open(url, timeout)
    except TimeoutError:
        raise Timeout(f"no WebSocket handshake from {address}", timeout) from None
    except InvalidURI:
        raise ValueError(f"{address} is not a WebSocket address: ws://HOST:PORT or "
                         f"wss://HOST:PORT") from None
    except InvalidStatus as refused:
        raise ConnectionLost(f"{address} refused the connection: HTTP "
                             f"{refused.response.status_code}") from None
    except (OSError, InvalidHandshake) as error:
        raise ConnectionLost(f"could not reach {address}: {error}") from None


def _open(url: str, timeout: float) -> Any:
    """An open WebSocket to ``url`` (entered by hand: the connection outlives the caller,
    closed by :meth:`Connection.close`)."""
    return ws_connect(url, max_size=None, open_timeout=bound(timeout)).__enter__()


def _batches(held: list[tuple[dict[str, Any], int]]) -> list[dict[str, Any]]:
    """Gathered requests (each with its text's bytes) as batches of at most TEXT_MESSAGES
    operations and about TEXT_BYTES each (a lone one as it is)."""
    batches: list[dict[str, Any]] = []
    chunk: list[dict[str, Any]] = []
    size = 0
    for op, length in held:
        if chunk and (size + length > TEXT_BYTES or len(chunk) >= TEXT_MESSAGES):
            batches.append(_batch(chunk))
            chunk, size = [], 0
        chunk.append(op)
        size += length + 1
    if chunk:
        batches.append(_batch(chunk))
    return batches


def _batch(ops: list[dict[str, Any]]) -> dict[str, Any]:
    return ops[0] if len(ops) == 1 else Batch(op="batch", ops=ops)


def _texts(requests: list[Request]) -> Iterator[str]:
    """The requests' texts joined into JSON arrays of at most TEXT_MESSAGES requests and
    about TEXT_BYTES (a lone request as it is)."""
    group: list[str] = []
    size = 0
    for request in requests:
        if group and (size + len(request.text) > TEXT_BYTES or len(group) >= TEXT_MESSAGES):
            yield _joined(group)
            group, size = [], 0
        group.append(request.text)
        size += len(request.text) + 1
    if group:
        yield _joined(group)


def _joined(texts: list[str]) -> str:
    return texts[0] if len(texts) == 1 else f"[{','.join(texts)}]"


def _with_query(url: str, **params: str) -> str:
    """``url`` with these query parameters set (replacing earlier values)."""
    parts = urlsplit(url)
    query = dict(parse_qsl(parts.query)) | params
    return urlunsplit(parts._replace(query=urlencode(query)))
