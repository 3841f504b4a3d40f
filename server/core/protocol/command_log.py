"""Changes clients made to a scene, as lines that make them again (a scene's journal).

A saved scene is its document plus the changes made since it was written: each request
that changed the scene is one line, ``{"client": "c7", "keep": false, "message": {…}}``,
and a client whose objects went when its grace period ended is ``{"client": "c7",
"left": true}``. :func:`replay` applies such lines to the scene the document made, through
a session of the same client, with the same checks as when they were first applied, so a
journal changed by hand can do no more than that client could have. Requests only change
what their message says (their effects depend on no clock), so the scene comes out as it was.
"""

from __future__ import annotations

import json
import logging
from typing import Any, Iterable

from ..kit.errors import VPError
from ..scene.scene import Scene
from .messages import encode
from .session import Session

log = logging.getLogger(__name__)


def applied_line(client_id: str, keep: bool, message: dict[str, Any]) -> bytes:
    """The line of a request that changed the scene."""
    return encode({"client": client_id, "keep": keep, "message": message}).encode() + b"\n"


def left_line(client_id: str) -> bytes:
    """The line of a client whose objects (those not kept) went when its grace ended."""
    return encode({"client": client_id, "left": True}).encode() + b"\n"


def replay(scene: Scene, lines: Iterable[bytes]) -> tuple[int, int]:
    """Make the changes of journal lines again; how many were applied and how many were
    not (a line cut short by a crash, or one the scene refuses: both are logged)."""
    sessions: dict[str, Session] = {}
    applied = skipped = 0
    for number, line in enumerate(lines, 1):
        try:
            if _apply(scene, sessions, line):
                applied += 1
                continue
        except Exception as error:  # a hand-made line must not stop the restore
            log.warning("scene %s: journal line %d not replayed: %r", scene.name, number,
                        error)
        skipped += 1
    return applied, skipped


def _apply(scene: Scene, sessions: dict[str, Session], line: bytes) -> bool:
    entry = _entry(line)
    client = entry["client"]
    session = sessions.get(client)
    if session is None:
        session = sessions[client] = Session(scene, client)
    if entry.get("left") is True:
        session.close()
        del sessions[client]
        return True
    session.operations.keep = entry.get("keep") is True
    answer = session.handle({**entry["message"], "id": 0})
    if answer is not None and answer["op"] == "error":
        log.warning("scene %s: a journal line of %s was refused again: %s", scene.name,
                    client, answer["message"])
        return False
    return True


def _entry(line: bytes) -> dict[str, Any]:
    entry = json.loads(line)
    if not isinstance(entry, dict) or not isinstance(entry.get("client"), str) or \
            not entry["client"].startswith("c") or not entry["client"][1:].isdigit() or \
            ("left" not in entry and not isinstance(entry.get("message"), dict)):
        raise VPError("not a journal line")
    return entry
