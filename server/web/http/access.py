"""Who may connect: tokens for controlling and viewing, the browser origins and the host
names allowed.

With a control token (``--token`` / ``VP_TOKEN``) a WebSocket controls only when it
presents it (``?token=``), and REST that changes things needs it
(``Authorization: Bearer …``); viewing (WebSockets as viewers, REST reads but
``/api/health``) stays open unless a view token is set too (``--view-token`` /
``VP_VIEW_TOKEN``; the control token also lets one view). A browser's
WebSocket must come from a page of this server or of an allowed origin (``--allow-origin``
/ ``VP_ALLOWED_ORIGINS``, comma-separated; ``*`` allows any); clients that send no
``Origin`` (scripts) are not browsers and pass; REST changes (import, upload) are held to
the same rule. Every request must name this server in its ``Host``: an IP address,
``localhost``, the name it was started on (``--host``; with ``0.0.0.0`` the machine's own
names) or one allowed with ``--allow-host`` (``VP_ALLOWED_HOSTS``); a page of another
site whose name was pointed at this server's address (DNS rebinding) names its own.
Tokens and resume keys are compared in constant time and never written to logs
(:class:`TokenRedaction` blanks them in every log record).
"""

from __future__ import annotations

import hmac
import ipaddress
import json
import logging
import re
import socket
from dataclasses import dataclass, field
from urllib.parse import urlsplit

from typing import Any

from starlette.requests import Request

from ...core.kit.errors import Forbidden

_SECRET_IN_TEXT = re.compile(r"((?:token|resume)=)[^&\s\"']*", re.IGNORECASE)
ANY_ADDRESS = ("0.0.0.0", "::", "")


@dataclass(frozen=True)
class AccessPolicy:
    """The server's tokens (None: not needed) and extra allowed browser origins."""

    control_token: str | None = None
    view_token: str | None = None
    origins: tuple[str, ...] = field(default_factory=tuple)
    hosts: tuple[str, ...] = field(default_factory=tuple)  # names besides the server's own
    # listening on loopback only: pages of any loopback origin (a user's own folder served
    # by `python3 -m http.server`, say) are this machine's user's, as the server is
    loopback: bool = False

    @classmethod
    def serving(cls, address: str, control_token: str | None = None,
                view_token: str | None = None, origins: tuple[str, ...] = (),
                hosts: tuple[str, ...] = ()) -> AccessPolicy:
        """The policy of a server listening on ``address``: its own names are allowed hosts
        (the machine's, when it listens on every address)."""
        own = [address]
        if address in ANY_ADDRESS:
            own += [socket.gethostname(), socket.getfqdn()]
        return cls(control_token, view_token, origins,
                   tuple(dict.fromkeys(h.lower() for h in [*own, *hosts] if h)),
                   loopback=_is_loopback(address))

    def check_role(self, role: str, token: str | None) -> None:
        """Refuse a connection whose token does not allow ``role``."""
        if role == "controller" and not _matches(token, self.control_token):
            raise Forbidden("controlling this server needs its token (?token=…)", role=role)
        if role == "viewer" and not self._may_view(token):
            raise Forbidden("viewing this server needs its view token (?token=…)", role=role)

    def trusts(self, token: str | None) -> bool:
        """Did a client present the control token (there is one)?"""
        return self.control_token is not None and _matches(token, self.control_token)

    def check_view(self, authorization: str | None, token: str | None) -> None:
        """Refuse a REST read without the view (or control) token, as a bearer or ?token=."""
        if not self._may_view(_bearer(authorization) or token):
            raise Forbidden("viewing this server needs its view token (Authorization: "
                            "Bearer … or ?token=…)")

    def _may_view(self, token: str | None) -> bool:
        return self.view_token is None or _matches(token, self.view_token) or \
            _matches(token, self.control_token)

    def check_change(self, authorization: str | None, origin: str | None = None,
                     host: str | None = None) -> None:
        """Refuse a REST change without ``Authorization: Bearer <control token>`` or from
        a browser page of another site (a form or ``fetch`` needs no token to be sent)."""
        if not _matches(_bearer(authorization), self.control_token):
            raise Forbidden("changing this server needs its token (Authorization: Bearer …)")
        self.check_origin(origin, host)

    def check_host(self, host: str | None) -> None:
        """Refuse a request whose ``Host`` is not a name of this server (DNS rebinding)."""
        name = _host_name(host)
        if name is None or "*" in self.hosts or name in self.hosts or _is_local(name):
            return
        raise Forbidden(f"this server does not answer to the name {name[:80]!r}; start it "
                        f"with --allow-host {name[:80]} (or VP_ALLOWED_HOSTS) to allow it",
                        host=name[:80])

    def allows_origin(self, origin: str | None, host: str | None = None) -> bool:
        """Whether a page of ``origin`` may use this server (no ``Origin``: not a browser;
        ``host``: the request's, whose own pages are allowed)."""
        if origin is None or "*" in self.origins or origin in self.origins:
            return True
        if host is not None and urlsplit(origin).netloc.lower() == host.lower():
            return True
        return self.loopback and _is_loopback_origin(origin)

    def check_origin(self, origin: str | None, host: str | None) -> None:
        """Refuse a browser page from another site, saying how to allow it."""
        if self.allows_origin(origin, host):
            return
        shown = (origin or "")[:80]
        raise Forbidden(f"pages of {shown} may not connect: start the server with "
                        f"--allow-origin {shown} (or VP_ALLOWED_ORIGINS={shown}) to allow them; "
                        f"allowed now are this server's own pages"
                        f"{', loopback pages' if self.loopback else ''}"
                        f"{' and ' + ', '.join(self.origins) if self.origins else ''}",
                        origin=shown)


def _host_name(host: str | None) -> str | None:
    """The name in a ``Host`` header, without its port (None: no header, as HTTP/1.0)."""
    if not host:
        return None
    host = host.strip().lower()
    if host.startswith("["):  # [::1]:8000
        return host[1:host.find("]")] if "]" in host else host
    return host.rsplit(":", 1)[0] if host.count(":") == 1 else host


def _is_local(name: str) -> bool:
    """An IP address (no name to point elsewhere) or ``localhost``."""
    if name == "localhost" or name.endswith(".localhost"):
        return True
    try:
        ipaddress.ip_address(name)
        return True
    except ValueError:
        return False


def _is_loopback(name: str) -> bool:
    """``localhost`` or a loopback address (127.0.0.0/8, ::1)."""
    name = name.strip("[]").lower()
    if name == "localhost" or name.endswith(".localhost"):
        return True
    try:
        return ipaddress.ip_address(name).is_loopback
    except ValueError:
        return False


def _is_loopback_origin(origin: str) -> bool:
    """An ``http(s)://`` origin on this machine (``localhost``, ``127.0.0.1``, ``[::1]``)."""
    try:
        parts = urlsplit(origin)
        return parts.scheme in ("http", "https") and _is_loopback(parts.hostname or "")
    except ValueError:  # a malformed origin (a bad port, say)
        return False


def _bearer(authorization: str | None) -> str | None:
    scheme, _, token = (authorization or "").partition(" ")
    return token if scheme.lower() == "bearer" and token else None


def _matches(presented: str | None, expected: str | None) -> bool:
    if expected is None:
        return True
    return presented is not None and hmac.compare_digest(presented.encode(), expected.encode())


class TokenRedaction(logging.Filter):
    """Blanks ``token=…`` and ``resume=…`` in a record's message and arguments (uvicorn logs
    request lines; a resume key lets whoever holds it be that client)."""

    def filter(self, record: logging.LogRecord) -> bool:
        if isinstance(record.msg, str):
            record.msg = _SECRET_IN_TEXT.sub(r"\1***", record.msg)
        if isinstance(record.args, tuple):
            record.args = tuple(_SECRET_IN_TEXT.sub(r"\1***", a) if isinstance(a, str) else a
                                for a in record.args)
        return True


def redact_tokens_in_logs() -> None:
    """Install :class:`TokenRedaction` on every handler of the root and uvicorn loggers."""
    redaction = TokenRedaction()
    for name in ("", "uvicorn", "uvicorn.access", "uvicorn.error"):
        logger = logging.getLogger(name)
        logger.addFilter(redaction)
        for handler in logger.handlers:
            handler.addFilter(redaction)


HEALTH = "/api/health"  # open to all: container health checks carry no token


def viewing_allowed(request: Request) -> None:
    """A FastAPI dependency of every REST route: reads need viewing rights."""
    if request.url.path != HEALTH:
        request.app.state.access.check_view(request.headers.get("authorization"),
                                            request.query_params.get("token"))


def changing_allowed(request: Request) -> None:
    """What a REST change must pass: the control token, and no page of another site."""
    request.app.state.access.check_change(request.headers.get("authorization"),
                                          request.headers.get("origin"),
                                          request.headers.get("host"))


class HostCheck:
    """ASGI middleware: every HTTP request and WebSocket handshake must name this server
    (:meth:`AccessPolicy.check_host`); others get a 403 ``forbidden`` naming the flag."""

    def __init__(self, app: Any, policy: AccessPolicy) -> None:
        self.app = app
        self.policy = policy

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        if scope["type"] in ("http", "websocket"):
            host = dict(scope["headers"]).get(b"host", b"").decode("latin-1")
            try:
                self.policy.check_host(host)
            except Forbidden as refusal:
                body = json.dumps({"code": refusal.code, "message": refusal.message}).encode()
                if scope["type"] == "websocket":  # a handshake refused with an HTTP answer
                    if "websocket.http.response" not in scope.get("extensions", {}):
                        await send({"type": "websocket.close", "code": 1008})  # a bare 403
                        return
                    await send({"type": "websocket.http.response.start", "status": 403,
                                "headers": [(b"content-type", b"application/json")]})
                    await send({"type": "websocket.http.response.body", "body": body})
                    return
                await send({"type": "http.response.start", "status": 403,
                            "headers": [(b"content-type", b"application/json")]})
                await send({"type": "http.response.body", "body": body})
                return
        await self.app(scope, receive, send)
