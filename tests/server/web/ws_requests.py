"""Small helpers for tests that speak the protocol over a real WebSocket."""

from __future__ import annotations

import json
from itertools import count
from typing import Any

from tests.conftest import WAIT_SECONDS

_ids = count(1_000_000)


def request_all(ws: Any, ops: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Send ops with ids and return their answers (skipping frames); fail on an error."""
    ids = []
    for op in ops:
        ids.append(next(_ids))
        ws.send(json.dumps({**op, "id": ids[-1]}))
    answers: dict[int, dict[str, Any]] = {}
    while len(answers) < len(ids):
        message = json.loads(ws.recv(timeout=WAIT_SECONDS))
        if message["op"] in ("ok", "error") and message["id"] in ids:
            assert message["op"] == "ok", message
            answers[message["id"]] = message
    return [answers[i] for i in ids]


def next_message(ws: Any, op: str, timeout: float = WAIT_SECONDS) -> dict[str, Any]:
    """The next message with this op (others are skipped)."""
    while True:
        message = json.loads(ws.recv(timeout=timeout))
        if message["op"] == op:
            return message


def wait_ticks(ws: Any, ticks: int = 2) -> None:
    """Return after this many frames (so that earlier changes are out of "added")."""
    for _ in range(ticks):
        next_message(ws, "frame")
