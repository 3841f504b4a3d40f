"""Reading and writing protocol messages, checked against ``protocol/schema/protocol.json``.

The schema is compiled once into Python code (fastjsonschema), one validator per message
definition, so a client message is checked in microseconds per operation.
"""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path
from typing import Any, Callable

import fastjsonschema
import orjson

from ..kit.errors import BadJSON, BadMessage, LimitExceeded, TooLarge, UnknownOp, show
from ..kit.limits import DEFAULT, Limits
from ..kit.wire_messages import CLIENT_MESSAGES

PROTOCOL_VERSION = 1
SCHEMA_PATH = Path(__file__).resolve().parents[3] / "protocol" / "schema" / "protocol.json"
CLIENT_OPS = tuple(CLIENT_MESSAGES)
MAX_REQUEST_ID = 2 ** 53 - 1  # the schema's requestId maximum: exact in every language


@cache
def schema() -> dict[str, Any]:
    """The protocol's JSON Schema."""
    return json.loads(SCHEMA_PATH.read_text())


@cache
def validator(definition: str) -> Callable[[Any], Any]:
    """A compiled check of one definition of the schema (raises JsonSchemaException)."""
    return fastjsonschema.compile({"$ref": f"#/$defs/{definition}", "$defs": schema()["$defs"]})


def _reject_constant(name: str) -> None:
    raise BadJSON(f"{name} is not JSON; send non-finite numbers as the string \"{name}\"")


def utf8_size(text: str, limit: int) -> int:
    """The UTF-8 size of ``text``, exact when it could be near ``limit`` (else a bound)."""
    if len(text) * 4 <= limit or len(text) > limit:
        return len(text)
    return len(text.encode("utf-8", "surrogatepass"))


def byte_size(data: str | bytes) -> int:
    """The size of a WebSocket message in bytes, as it travelled (UTF-8)."""
    if isinstance(data, bytes) or data.isascii():
        return len(data)
    return len(data.encode("utf-8", "surrogatepass"))


def decode(data: str | bytes, limits: Limits = DEFAULT) -> list[Any]:
    """The messages in one WebSocket text message (an object, or an array of them)."""
    if not isinstance(data, str):
        raise BadMessage("binary WebSocket messages are not part of the protocol; "
                         "send JSON as text messages")
    size = utf8_size(data, limits.message_bytes)
    if size > limits.message_bytes:
        raise TooLarge(f"message of {size} bytes is over the limit of {limits.message_bytes} "
                       f"bytes", limit="messageBytes", value=limits.message_bytes)
    try:
        value = orjson.loads(data)
    except orjson.JSONDecodeError:  # the standard library says why (and reads what orjson
        value = _strict_loads(data)  # refuses but JSON allows: lone surrogates, huge ints)
    if not isinstance(value, list):
        return [value]
    if len(value) > limits.messages_per_text:
        raise LimitExceeded(f"{len(value)} messages in one text; at most "
                            f"{limits.messages_per_text}", limit="messagesPerText",
                            value=limits.messages_per_text)
    return value


def _strict_loads(data: str) -> Any:
    try:
        return json.loads(data, parse_constant=_reject_constant)
    except RecursionError:
        raise BadJSON("not valid JSON: nested too deeply") from None
    except ValueError as error:
        raise BadJSON(f"not valid JSON: {error}") from None


def request_id(message: Any) -> int | None:
    """The id a message asks its answer to carry, if it is a valid one."""
    if isinstance(message, dict):
        value = message.get("id")
        if isinstance(value, int) and not isinstance(value, bool) and 0 <= value <= MAX_REQUEST_ID:
            return value
    return None


def check_client_message(message: Any) -> dict[str, Any]:
    """``message`` if it is a well-formed client message; else the error that says why."""
    if not isinstance(message, dict):
        raise BadMessage(f"a message must be a JSON object, got {show(message)}")
    op = message.get("op")
    if op not in CLIENT_OPS:
        raise UnknownOp(f"unknown op {show(op)}; the ops are {', '.join(CLIENT_OPS)}")
    try:
        if not _passes_in_parts(message, op):
            validator(op)(message)  # the whole message: the schema's own error if any
    except fastjsonschema.JsonSchemaValueException as error:
        raise _schema_refusal(error, op, "message") from None
    return message


def _passes_in_parts(message: dict[str, Any], op: str) -> bool:
    """True when the message is valid, checked by parts that are cheaper than the whole;
    False when that could not tell (the caller then checks it whole).

    Each shortcut accepts exactly what its definition does: a call's ``args`` of numbers,
    booleans and nulls are each an ``arg`` as they stand (the compiled check builds an error
    path per item), and the rest of a call without an id is valid or not by its object and
    method alone (kept, so an animation's calls on the same motors are checked once); a
    batch's operations past the first, each a create, call or delete without an id, are
    its ``batchOp`` definition's branch for that op (whose compiled form tries every branch
    by raising an exception: three quarters of a batch's check)."""
    try:
        if op == "call" and _scalars_only(message.get("args")):
            _check_call_without_args(message)
            return True
        if op != "batch" or type(ops := message.get("ops")) is not list or \
                not 1 < len(ops) <= _max_batch():
            return False
        for inner in ops[1:]:
            if type(inner) is not dict or inner.get("op") not in _batch_ops() or "id" in inner:
                return False
            if not _passes_in_parts(inner, inner["op"]):
                validator(inner["op"])(inner)
        validator(op)({**message, "ops": ops[:1]})
        return True
    except fastjsonschema.JsonSchemaValueException:
        return False


def check_document(document: Any) -> None:
    """Nothing when ``document`` has the form of a scene document (``sceneDocument``),
    else :class:`BadMessage` saying where it differs."""
    if not isinstance(document, dict) or document.get("format") != "virtual-prosthetics-scene":
        raise BadMessage("not a scene document: it needs \"format\": "
                         "\"virtual-prosthetics-scene\" (what GET /api/scenes/{scene}/export gives)")
    try:
        validator("sceneDocument")(document)
    except fastjsonschema.JsonSchemaValueException as error:
        raise _schema_refusal(error, "scene document", "document") from None


def _schema_refusal(error: fastjsonschema.JsonSchemaValueException, what: str,
                    whole: str) -> BadMessage:
    """What the schema found wrong, where (``whole`` when it is the value itself)."""
    where = "/".join(str(p) for p in error.path[1:]) or whole
    complaint = error.message.split(" ", 1)[1] if " " in error.message else error.message
    return BadMessage(f"{what}: {where}: {complaint}", path=where)


def _scalars_only(args: Any) -> bool:
    """True for a list of plain numbers, booleans and nulls (setAngles' angles,
    spreadFingers' angle and thumb) no longer than the schema's ``args`` allows: each is an
    ``arg`` as it stands, so the compiled check (which builds an error path per item) can
    leave them out; the schema stays the one source."""
    return type(args) is list and len(args) <= _max_args() and \
        all(type(a) in _SCALARS or a is None for a in args)


_SCALARS = (float, int, bool)
_CALL_KEYS = frozenset(("op", "object", "method", "args"))
CHECKED_CALLS = 4096  # (object, method) pairs a process keeps as checked
_checked_calls: dict[tuple[str, str], None] = {}


def _check_call_without_args(message: dict[str, Any]) -> None:
    """The schema's check of a call with its args left out (raises as it does); a call of
    exactly op, object, method and args is valid by its object and method alone, and a
    pair found valid once is not checked again."""
    key = (message.get("object"), message.get("method"))
    kept = type(key[0]) is str and type(key[1]) is str and message.keys() == _CALL_KEYS
    if kept and key in _checked_calls:
        return
    validator("call")({**message, "args": []})
    if kept:
        if len(_checked_calls) >= CHECKED_CALLS:
            _checked_calls.clear()
        _checked_calls[key] = None  # type: ignore[index]


@cache
def _max_args() -> int:
    return schema()["$defs"]["args"]["maxItems"]


@cache
def _max_batch() -> int:
    return schema()["$defs"]["batch"]["properties"]["ops"]["maxItems"]


@cache
def _batch_ops() -> tuple[str, ...]:
    return tuple(schema()["$defs"]["batchOp"]["properties"]["op"]["enum"])


def check_server_message(message: dict[str, Any]) -> None:
    """Raise ``JsonSchemaException`` if a server message breaks the schema (tests use it)."""
    validator("serverMessage")(message)


def encode(message: dict[str, Any]) -> str:
    """One message as compact JSON text (the standard library's text, made by orjson: a
    frame of fifty hands in 25 µs instead of 450). Non-finite numbers travel as strings
    (:mod:`server.core.kit.numbers`); a bare one would be a server bug, and orjson writes it
    as null, which the schema refuses where a number belongs (the tests check messages)."""
    try:
        return orjson.dumps(message, option=orjson.OPT_SERIALIZE_NUMPY).decode()
    except TypeError:  # what orjson does not write (integers beyond 64 bits)
        return json.dumps(message, separators=(",", ":"), allow_nan=False)
