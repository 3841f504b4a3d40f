"""Reading and writing protocol messages, checked against ``protocol/schema/protocol.json``."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path
from typing import Any

import jsonschema

from ..errors import BadJSON, BadMessage, LimitExceeded, TooLarge, UnknownOp

PROTOCOL_VERSION = 1
SCHEMA_PATH = Path(__file__).resolve().parents[2] / "protocol" / "schema" / "protocol.json"
CLIENT_OPS = ("create", "call", "delete", "batch", "ping")

LIMITS: dict[str, int] = {
    "messageBytes": 1 << 20,   # one WebSocket text message
    "messagesPerText": 10_000,  # messages in one array
    "batchOps": 10_000,
    "sceneObjects": 50_000,
    "watchedSensors": 1_000,   # sensors whose readings every frame carries
}


@cache
def schema() -> dict[str, Any]:
    """The protocol's JSON Schema."""
    return json.loads(SCHEMA_PATH.read_text())


@cache
def _validator(definition: str) -> jsonschema.protocols.Validator:
    root = schema()
    cls = jsonschema.validators.validator_for(root)
    return cls({"$ref": f"#/$defs/{definition}", "$defs": root["$defs"]})


def _reject_constant(name: str) -> None:
    raise BadJSON(f"{name} is not JSON; send non-finite numbers as the string \"{name}\"")


def decode(text: str | bytes) -> list[Any]:
    """The messages in one WebSocket text message (an object, or an array of them)."""
    if len(text) > LIMITS["messageBytes"]:
        raise TooLarge(f"message of {len(text)} bytes is over the limit of "
                       f"{LIMITS['messageBytes']} bytes", limit=LIMITS["messageBytes"])
    try:
        value = json.loads(text, parse_constant=_reject_constant)
    except (ValueError, RecursionError) as error:
        raise BadJSON(f"not valid JSON: {error}") from None
    if not isinstance(value, list):
        return [value]
    if len(value) > LIMITS["messagesPerText"]:
        raise LimitExceeded(f"{len(value)} messages in one text; at most "
                            f"{LIMITS['messagesPerText']}", limit=LIMITS["messagesPerText"])
    return value


def check_client_message(message: Any) -> dict[str, Any]:
    """``message`` if it is a well-formed client message; else the error that says why."""
    if not isinstance(message, dict):
        raise BadMessage(f"a message must be a JSON object, got {type(message).__name__}")
    op = message.get("op")
    if op not in CLIENT_OPS:
        raise UnknownOp(f"unknown op {op!r}; the ops are {', '.join(CLIENT_OPS)}", op=op)
    error = jsonschema.exceptions.best_match(_validator(op).iter_errors(message))
    if error is not None:
        where = "/".join(str(p) for p in error.absolute_path) or "message"
        raise BadMessage(f"{op}: {where}: {error.message}", path=where)
    return message


def check_server_message(message: dict[str, Any]) -> None:
    """Raise ``jsonschema.ValidationError`` if a server message breaks the schema (tests use it)."""
    _validator("serverMessage").validate(message)


def encode(message: dict[str, Any]) -> str:
    """One message as compact JSON text; a bare non-finite number is a server bug."""
    return json.dumps(message, separators=(",", ":"), allow_nan=False)
