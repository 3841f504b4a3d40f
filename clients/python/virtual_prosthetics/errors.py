"""Exceptions of the Python client.

Hierarchy::

    VPError                 base of everything this package raises
    ├── ServerError         the server answered a request with an error
    ├── ProtocolError       the server sent something the protocol does not define
    ├── ConnectionLost      the WebSocket closed (or never opened)
    └── Timeout             the server did not answer in time

    ServerWarning           (a UserWarning) the server did what was asked, with a remark
"""

from __future__ import annotations

from typing import Any

from .waiting import ENVIRONMENT


class VPError(Exception):
    """Base of every exception raised by the client."""


class ServerError(VPError):
    """An error answer of the server, with the wire fields as attributes.

    ``code`` is one of the protocol's codes (``wrong_type``, ``unknown_object``, …),
    ``message`` says what was wrong, ``request`` names the op that failed and
    ``details`` holds structured facts (object id, argument, batch index).
    """

    def __init__(self, code: str, message: str, request: str | None = None,
                 details: dict[str, Any] | None = None) -> None:
        super().__init__(f"{code}: {message}")
        self.code = code
        self.message = message
        self.request = request
        self.details = details or {}

    @classmethod
    def from_wire(cls, wire: dict[str, Any]) -> ServerError:
        """The exception for an ``error`` message."""
        return cls(wire["code"], wire["message"], wire.get("request"), wire.get("details"))


class ProtocolError(VPError):
    """The server sent a message the protocol does not define (the client stops reading)."""


class ConnectionLost(VPError):
    """The connection to the server is closed."""


class Timeout(VPError):
    """The server did not answer within the time limit: ``what`` did not come within
    ``seconds``; the message names how to wait longer."""

    HOW_TO_WAIT_LONGER = f"connect(..., timeout=S) or {ENVIRONMENT}=S waits longer"

    def __init__(self, what: str, seconds: float) -> None:
        super().__init__(f"{what} within {seconds:g} s ({self.HOW_TO_WAIT_LONGER})")
        self.what = what
        self.seconds = seconds


class ServerWarning(UserWarning):
    """A remark in the server's answer to a request that succeeded (``warnings.warn``).

    For example: ``attach_to_slot`` with a slot index the parent does not have attaches
    the part to the parent itself, as 1.0 did, and says so.
    """
