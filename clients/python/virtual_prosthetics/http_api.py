"""The server's REST side, for what the WebSocket does not carry: mesh files going up,
robot files coming down. Same server, same token as the session's WebSocket."""

from __future__ import annotations

import json
import urllib.error
import urllib.request
from urllib.parse import quote

from .errors import ConnectionLost, ServerError, Timeout
from .session import Session
from .viewer_cell import http_of
from .waiting import bound


def http_url(session: Session) -> str:
    """The session's server as http(s)://host:port."""
    return http_of(session.url)


def scene_path(session: Session, *names: str) -> str:
    """``/api/scenes/{scene}/…`` with each name quoted."""
    return "/api/scenes/" + "/".join(quote(n, safe="") for n in (session.name, *names))


def request(session: Session, path: str, what: str, data: bytes | None = None) -> bytes:
    """The body the server answers ``path`` with (POSTing ``data`` when given); its refusal
    as :class:`ServerError` (code and message as on the WebSocket, ``what`` as the call)."""
    headers = {**({"Content-Type": "application/octet-stream"} if data is not None else {}),
               **({"Authorization": f"Bearer {session.token}"} if session.token else {})}
    http = http_url(session)
    call = urllib.request.Request(f"{http}{path}", data=data, headers=headers,
                                  method="POST" if data is not None else "GET")
    try:
        with urllib.request.urlopen(call, timeout=bound(session.connection.timeout)) as answer:
            return answer.read()
    except TimeoutError:
        raise Timeout(f"no answer to {what} from {http}", session.connection.timeout) from None
    except urllib.error.HTTPError as error:
        body = json.loads(error.read() or b"{}")
        raise ServerError(body.get("code", "http_error"), body.get("message", str(error)),
                          what, body.get("details")) from None
    except urllib.error.URLError as error:
        if isinstance(error.reason, TimeoutError):
            raise Timeout(f"no answer to {what} from {http}", session.connection.timeout) from None
        raise ConnectionLost(f"could not reach {http}: {error.reason}") from None
