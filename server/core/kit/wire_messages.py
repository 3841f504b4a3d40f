"""One typed definition per wire message. Written by ``make generate``
(generate/message_types.py) from protocol/schema/protocol.json; do not edit (a test
fails when the two differ).

Messages stay plain dicts on the wire and in the code: ``Frame(op="frame", seq=1, time=0.0)``
makes one; the definitions say which keys each has, for readers and type checkers.
"""

# (no `from __future__ import annotations`: TypedDict reads NotRequired from the
# evaluated annotations)
from typing import Any, Literal, NotRequired, TypedDict


class Create(TypedDict):
    op: Literal['create']
    id: NotRequired[int]
    object: str
    type: str
    args: NotRequired[list[Any]]


class Call(TypedDict):
    op: Literal['call']
    id: NotRequired[int]
    object: str
    method: str
    args: NotRequired[list[Any]]


class Delete(TypedDict):
    op: Literal['delete']
    id: NotRequired[int]
    object: str


class Batch(TypedDict):
    op: Literal['batch']
    id: NotRequired[int]
    ops: list[dict[str, Any]]


class Ping(TypedDict):
    op: Literal['ping']
    id: NotRequired[int]


class Hello(TypedDict):
    op: Literal['hello']
    protocol: Literal[1]
    client: str
    role: str
    scene: str
    time: float
    tickRate: float
    limits: dict[str, int]
    engine: str
    slots: dict[str, int]
    physics: dict[str, Any]
    resume: NotRequired[str]


class Snapshot(TypedDict):
    op: Literal['snapshot']
    scene: str
    seq: int
    time: float
    camera: dict[str, Any]
    physics: dict[str, Any]
    caption: NotRequired[str]
    nodes: list[dict[str, Any]]
    contacts: list[list[str]]
    forces: NotRequired[dict[str, float]]
    sensors: NotRequired[dict[str, dict[str, Any]]]


class Ok(TypedDict):
    op: Literal['ok']
    id: int
    result: NotRequired[Any]
    changes: NotRequired[dict[str, Any]]
    warnings: NotRequired[list[str]]


class Error(TypedDict):
    op: Literal['error']
    id: int | None
    code: str
    message: str
    request: NotRequired[str]
    details: NotRequired[dict[str, Any]]


class Frame(TypedDict):
    op: Literal['frame']
    seq: int
    time: float
    angles: NotRequired[Any]
    poses: NotRequired[Any]
    updates: NotRequired[Any]
    camera: NotRequired[dict[str, Any]]
    physics: NotRequired[dict[str, Any]]
    caption: NotRequired[str]
    contacts: NotRequired[dict[str, Any]]
    sensors: NotRequired[dict[str, dict[str, Any]]]
    forces: NotRequired[dict[str, float]]
    limited: NotRequired[dict[str, int]]


class Added(TypedDict):
    op: Literal['added']
    seq: int
    nodes: list[dict[str, Any]]


class Removed(TypedDict):
    op: Literal['removed']
    seq: int
    ids: list[str]


class WarningMessage(TypedDict):
    op: Literal['warning']
    code: str
    message: str


CLIENT_MESSAGES: dict[str, type] = {"create": Create, "call": Call, "delete": Delete, "batch": Batch, "ping": Ping}
SERVER_MESSAGES: dict[str, type] = {"hello": Hello, "snapshot": Snapshot, "ok": Ok, "error": Error, "frame": Frame, "added": Added, "removed": Removed, "warning": WarningMessage}
