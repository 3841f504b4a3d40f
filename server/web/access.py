"""Who may connect: tokens for controlling and viewing, and the browser origins allowed.

With a control token (``--token`` / ``VP_TOKEN``) a WebSocket controls only when it
presents it (``?token=``), and REST that changes things needs it
(``Authorization: Bearer …``); viewing (WebSockets as viewers, REST reads but
``/api/health``) stays open unless a view token is set too (``--view-token`` /
``VP_VIEW_TOKEN``; the control token also lets one view). A browser's
WebSocket must come from a page of this server or of an allowed origin (``--allow-origin``
/ ``VP_ALLOWED_ORIGINS``, comma-separated; ``*`` allows any); clients that send no
``Origin`` (scripts) are not browsers and pass. Tokens are compared in constant time and
never written to logs (:class:`TokenRedaction` blanks them in every log record).
"""

from __future__ import annotations

import hmac
import logging
import re
from dataclasses import dataclass, field
from urllib.parse import urlsplit

from starlette.requests import Request

from ..errors import Forbidden

_TOKEN_IN_TEXT = re.compile(r"(token=)[^&\s\"']*", re.IGNORECASE)


@dataclass(frozen=True)
class AccessPolicy:
    """The server's tokens (None: not needed) and extra allowed browser origins."""

    control_token: str | None = None
    view_token: str | None = None
    origins: tuple[str, ...] = field(default_factory=tuple)

    def check_role(self, role: str, token: str | None) -> None:
        """Refuse a connection whose token does not allow ``role``."""
        if role == "controller" and not _matches(token, self.control_token):
            raise Forbidden("controlling this server needs its token (?token=…)", role=role)
        if role == "viewer" and not self._may_view(token):
            raise Forbidden("viewing this server needs its view token (?token=…)", role=role)

    def check_view(self, authorization: str | None, token: str | None) -> None:
        """Refuse a REST read without the view (or control) token, as a bearer or ?token=."""
        if not self._may_view(_bearer(authorization) or token):
            raise Forbidden("viewing this server needs its view token (Authorization: "
                            "Bearer … or ?token=…)")

    def _may_view(self, token: str | None) -> bool:
        return self.view_token is None or _matches(token, self.view_token) or \
            _matches(token, self.control_token)

    def check_change(self, authorization: str | None) -> None:
        """Refuse a REST change without ``Authorization: Bearer <control token>``."""
        if not _matches(_bearer(authorization), self.control_token):
            raise Forbidden("changing this server needs its token (Authorization: Bearer …)")

    def check_origin(self, origin: str | None, host: str | None) -> None:
        """Refuse a browser page from another site (no ``Origin``: not a browser)."""
        if origin is None or "*" in self.origins or origin in self.origins:
            return
        if host is not None and urlsplit(origin).netloc.lower() == host.lower():
            return
        raise Forbidden(f"pages of {origin[:80]} may not connect; allowed are this server's "
                        f"own pages{' and ' + ', '.join(self.origins) if self.origins else ''}",
                        origin=origin[:80])


def _bearer(authorization: str | None) -> str | None:
    scheme, _, token = (authorization or "").partition(" ")
    return token if scheme.lower() == "bearer" and token else None


def _matches(presented: str | None, expected: str | None) -> bool:
    if expected is None:
        return True
    return presented is not None and hmac.compare_digest(presented.encode(), expected.encode())


class TokenRedaction(logging.Filter):
    """Blanks ``token=…`` in a record's message and arguments (uvicorn logs request lines)."""

    def filter(self, record: logging.LogRecord) -> bool:
        if isinstance(record.msg, str):
            record.msg = _TOKEN_IN_TEXT.sub(r"\1***", record.msg)
        if isinstance(record.args, tuple):
            record.args = tuple(_TOKEN_IN_TEXT.sub(r"\1***", a) if isinstance(a, str) else a
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
