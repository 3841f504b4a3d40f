"""Every error the server reports, one class per wire ``code``.

Hierarchy::

    VPError                      base: code, message, details
    ├── ProtocolError            the message itself is unusable
    │   ├── BadJSON              bad_json       text that is not JSON
    │   ├── BadMessage           bad_message    JSON that breaks the protocol schema
    │   ├── UnknownOp            unknown_op     an "op" the protocol does not define
    │   └── TooLarge             too_large      a message over the size limit
    ├── LookupFailure            a name or id that does not exist
    │   ├── UnknownType          unknown_type   create with a type the API lacks
    │   ├── UnknownMethod        unknown_method call of a method the type lacks
    │   ├── UnknownObject        unknown_object an id no object in the scene has
    │   ├── UnknownScene         unknown_scene  a scene name that is not served
    │   ├── UnknownAsset         unknown_asset  a mesh file that is not bundled or uploaded
    │   └── UnknownRecording     unknown_recording a recording id the server does not hold
    ├── ArgumentError            arguments of a create or call
    │   ├── BadArguments         bad_arguments  wrong number of arguments
    │   ├── WrongType            wrong_type     an argument of the wrong kind
    │   ├── OutOfRange           out_of_range   a value outside what is allowed
    │   └── BadAsset             bad_asset      an uploaded file that is not a usable glTF mesh
    ├── ConflictError            a request that contradicts the scene
    │   ├── DuplicateId          duplicate_id   an id already (or once) in use
    │   ├── ForeignId            foreign_id     an id without this client's prefix
    │   ├── Cycle                cycle          attaching a node below itself
    │   ├── NotPaused            not_paused     stepping a scene whose clock runs
    │   └── RecordingBusy        recording_busy starting a second recording of a scene, or
    │                                           downloading one still being recorded
    ├── RecordingDamaged         recording_damaged a recording whose file cannot be read
    │                                           (cut short, changed, not a recording)
    ├── Forbidden                forbidden      a viewer asked to change something
    ├── LimitExceeded            limit_exceeded a documented limit was reached
    ├── StorageFailure           storage_failure a file the server must write cannot be
    │                                           (a full disk, a folder it may not write)
    ├── BusUnavailable           bus_unavailable a cluster's gateway cannot reach its bus
    │                                           (the scenes its workers run are out of reach)
    └── InternalError            internal       a server fault (a bug): reported, not hidden

The wire form (``{"op": "error", "id", "code", "message", "details"}``) is defined in
``protocol/schema/protocol.json``; :meth:`VPError.to_wire` produces it. Whatever a client
sent, an error stays small: messages are cut at ``MAX_MESSAGE`` characters, detail strings
at ``MAX_DETAIL``, and values a client sent are shown through :func:`show`.
"""

from __future__ import annotations

from typing import Any

from .limits import DEFAULT as DEFAULT_LIMITS
from .wire_messages import Error as ErrorMessage

MAX_MESSAGE = 500
MAX_DETAIL = 120


def show(value: Any) -> str:
    """A short, safe rendering of a value a client sent (never deep, never long)."""
    if isinstance(value, bool) or value is None:
        return "true" if value is True else "false" if value is False else "null"
    if isinstance(value, int) and abs(value) >= 10 ** 15:
        return f"a {len(str(abs(value))) if abs(value) < 10 ** 4000 else 'huge'}-digit integer"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return repr(value) if len(value) <= 40 else repr(value[:37]) + f"... ({len(value)} characters)"
    if isinstance(value, dict):
        return f"an object with {len(value)} key{'s' * (len(value) != 1)}"
    if isinstance(value, list):
        return f"an array of {len(value)} item{'s' * (len(value) != 1)}"
    return type(value).__name__


_CONFIGURABLE = frozenset(DEFAULT_LIMITS.wire())


def _cut(text: str, limit: int) -> str:
    return text if len(text) <= limit else text[:limit - 3] + "..."


class VPError(Exception):
    """Base of every reported error: a machine-readable ``code`` and a human ``message``."""

    code = "error"

    def __init__(self, message: str, **details: Any) -> None:
        limit = details.get("limit")
        if limit in _CONFIGURABLE and "flag" not in details:
            # every refusal by a limit says how the server's operator changes it
            details["flag"] = f"--limit {limit}=N"
            message = f"{message} (limit {limit}; vp-server --limit {limit}=N changes it)"
        super().__init__(message)
        self.message = message
        self.details = {k: v for k, v in details.items() if v is not None}

    def __reduce__(self) -> tuple[Any, ...]:
        # the details travel too when an error crosses from a scene's process
        return _rebuild, (type(self), self.message, self.details)

    def to_wire(self, request_id: int | None = None, op: str | None = None) -> ErrorMessage:
        """The error message that answers a request (``request_id`` None: fire-and-forget)."""
        wire = ErrorMessage(op="error", id=request_id, code=self.code,
                            message=_cut(self.message, MAX_MESSAGE))
        if op is not None:
            wire["request"] = op
        if self.details:
            wire["details"] = self.wire_details()
        return wire

    def wire_details(self) -> dict[str, Any]:
        """The details, each a short string, a number, a boolean or null."""
        return {k: _cut(v, MAX_DETAIL) if isinstance(v, str)
                else v if isinstance(v, (bool, float)) or v is None
                else v if isinstance(v, int) and abs(v) < 2 ** 53 else show(v)
                for k, v in self.details.items()}


def _rebuild(cls: type[VPError], message: str, details: dict[str, Any]) -> VPError:
    return cls(message, **details)


class ProtocolError(VPError):
    """The message cannot be read as a protocol message."""


class BadJSON(ProtocolError):
    code = "bad_json"


class BadMessage(ProtocolError):
    code = "bad_message"


class UnknownOp(ProtocolError):
    code = "unknown_op"


class TooLarge(ProtocolError):
    code = "too_large"


class LookupFailure(VPError):
    """A type, method, object or scene that does not exist."""


class UnknownType(LookupFailure):
    code = "unknown_type"


class UnknownMethod(LookupFailure):
    code = "unknown_method"


class UnknownObject(LookupFailure):
    code = "unknown_object"


class UnknownScene(LookupFailure):
    code = "unknown_scene"


class UnknownRecording(LookupFailure):
    code = "unknown_recording"


class UnknownAsset(LookupFailure):
    code = "unknown_asset"


class ArgumentError(VPError):
    """Arguments that do not fit the called constructor or method."""


class BadArguments(ArgumentError):
    code = "bad_arguments"


class WrongType(ArgumentError):
    code = "wrong_type"


class OutOfRange(ArgumentError):
    code = "out_of_range"


class BadAsset(ArgumentError):
    code = "bad_asset"


class ConflictError(VPError):
    """A request that contradicts the current scene."""


class DuplicateId(ConflictError):
    code = "duplicate_id"


class ForeignId(ConflictError):
    code = "foreign_id"


class Cycle(ConflictError):
    code = "cycle"


class NotPaused(ConflictError):
    code = "not_paused"


class RecordingBusy(ConflictError):
    code = "recording_busy"


class RecordingDamaged(VPError):
    code = "recording_damaged"


class Forbidden(VPError):
    code = "forbidden"


class LimitExceeded(VPError):
    """A limit of :mod:`server.core.kit.limits` was reached: ``details.limit`` names it,
    ``details.value`` is its value and ``details.flag`` the server option that changes it
    (``too_large`` carries the same details for ``messageBytes``)."""

    code = "limit_exceeded"


class StorageFailure(VPError):
    code = "storage_failure"


class BusUnavailable(VPError):
    """A gateway's bus is unreachable: ``details.bus`` names it (its address without
    credentials); the request may be tried again once it is back."""

    code = "bus_unavailable"


class InternalError(VPError):
    code = "internal"


ERROR_CODES: tuple[str, ...] = tuple(
    cls.code for cls in (BadJSON, BadMessage, UnknownOp, TooLarge, UnknownType, UnknownMethod,
                         UnknownObject, UnknownScene, UnknownAsset, UnknownRecording, BadArguments,
                         WrongType, OutOfRange, BadAsset, DuplicateId, ForeignId, Cycle, NotPaused,
                         RecordingBusy, RecordingDamaged, Forbidden, LimitExceeded, StorageFailure,
                         BusUnavailable, InternalError)
)
