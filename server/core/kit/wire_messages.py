"""One typed definition per wire message (``protocol/schema/protocol.json`` is the source;
tests/server/core/kit/test_wire_messages.py fails when the two differ).

Messages stay plain dicts on the wire and in the code (``Frame(op="frame", …)`` makes one);
these definitions say which keys each has, for readers and type checkers. In the kit so
that every layer that builds a message (the scene its frames, the protocol its answers,
``server.errors`` the error) can name its type.
"""

# (no `from __future__ import annotations`: TypedDict reads NotRequired from the
# evaluated annotations)
from typing import Any, Literal, NotRequired, TypedDict

# --- client to server ---------------------------------------------------------------------


class Create(TypedDict):
    op: Literal["create"]
    id: NotRequired[int | str]
    object: str
    type: str
    args: NotRequired[list[Any]]


class Call(TypedDict):
    op: Literal["call"]
    id: NotRequired[int | str]
    object: str
    method: str
    args: NotRequired[list[Any]]


class Delete(TypedDict):
    op: Literal["delete"]
    id: NotRequired[int | str]
    object: str


class Batch(TypedDict):
    op: Literal["batch"]
    id: NotRequired[int | str]
    ops: list[dict[str, Any]]


class Ping(TypedDict):
    op: Literal["ping"]
    id: NotRequired[int | str]


# --- server to client ---------------------------------------------------------------------


class Hello(TypedDict):
    op: Literal["hello"]
    protocol: int
    client: str
    role: str
    scene: str
    time: float
    tickRate: float
    limits: dict[str, Any]
    engine: str
    slots: dict[str, int]
    resume: NotRequired[str]


class Snapshot(TypedDict):
    op: Literal["snapshot"]
    scene: str
    seq: int
    time: float
    camera: dict[str, Any]
    nodes: list[dict[str, Any]]
    contacts: list[list[str]]


class Ok(TypedDict):
    op: Literal["ok"]
    id: int | str | None
    result: NotRequired[Any]
    changes: NotRequired[dict[str, Any]]
    warnings: NotRequired[list[str]]


class Error(TypedDict):
    op: Literal["error"]
    id: int | str | None
    code: str
    message: str
    request: NotRequired[str]
    details: NotRequired[dict[str, Any]]


class Frame(TypedDict):
    op: Literal["frame"]
    seq: int
    time: float
    angles: NotRequired[dict[str, float]]
    poses: NotRequired[dict[str, list[float]]]
    updates: NotRequired[dict[str, dict[str, Any]]]
    camera: NotRequired[dict[str, Any]]
    contacts: NotRequired[dict[str, list[list[str]]]]
    sensors: NotRequired[dict[str, dict[str, Any]]]
    limited: NotRequired[dict[str, int]]


class Added(TypedDict):
    op: Literal["added"]
    seq: int
    nodes: list[dict[str, Any]]


class Removed(TypedDict):
    op: Literal["removed"]
    seq: int
    ids: list[str]


class WarningMessage(TypedDict):
    op: Literal["warning"]
    code: str
    message: str


CLIENT_MESSAGES: dict[str, type] = {"create": Create, "call": Call, "delete": Delete,
                                    "batch": Batch, "ping": Ping}
SERVER_MESSAGES: dict[str, type] = {"hello": Hello, "snapshot": Snapshot, "ok": Ok,
                                    "error": Error, "frame": Frame, "added": Added,
                                    "removed": Removed, "warning": WarningMessage}
