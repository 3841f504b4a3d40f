"""A scene's journal: the changes clients made, made again on the document written before."""

from __future__ import annotations

import json

from server.core.protocol.command_log import applied_line, left_line, replay
from server.core.scene.scene import Scene
from server.core.protocol.scene_document import encode_document, export_scene, import_scene
from server.core.protocol.session import Session


def journaled(scene: Scene, client: str, keep: bool = False) -> tuple[Session, list[bytes]]:
    """A session whose changes are written down as a journal would be."""
    lines: list[bytes] = []
    session = Session(scene, client)
    session.operations.keep = keep
    session.on_change = lambda s, message: lines.append(
        applied_line(s.client_id, s.operations.keep, message))
    return session, lines


def send(session: Session, *messages: dict) -> None:
    for answer in session.receive(json.dumps(list(messages))):
        assert answer["op"] == "ok", answer


def test_replaying_the_journal_on_the_document_gives_the_scene_again():
    scene = Scene("lab")
    session, lines = journaled(scene, "c4")
    send(session, {"op": "create", "object": "c4.1", "type": "EdgedHand", "id": 1})
    document = export_scene(scene)  # written here; what follows is journaled
    lines.clear()
    send(session,
         {"op": "call", "object": "c4.1", "method": "flexFingers", "args": [0.6], "id": 2},
         {"op": "create", "object": "c4.2", "type": "Box", "args": [0.2, 0.3, 0.4], "id": 3},
         {"op": "call", "object": "c4.2", "method": "setPosition", "args": [1, 2, 3], "id": 4},
         {"op": "call", "object": "c4.2", "method": "keep", "id": 5},
         {"op": "create", "object": "c4.3", "type": "Ball", "id": 6},
         {"op": "delete", "object": "c4.3", "id": 7},
         {"op": "call", "object": "scene", "method": "setCameraPosition", "args": [3, 4, 5], "id": 8},
         {"op": "call", "object": "c4.1", "method": "getAngles", "id": 9})  # reads: no line
    assert len(lines) == 7
    copy = Scene("lab")
    import_scene(copy, document)
    assert replay(copy, lines) == (7, 0)
    assert encode_document(export_scene(copy)) == encode_document(export_scene(scene))


def test_a_client_that_left_takes_what_it_did_not_keep_along_again():
    scene = Scene("lab")
    session, lines = journaled(scene, "c4")
    send(session, {"op": "create", "object": "c4.1", "type": "Box", "id": 1},
         {"op": "create", "object": "c4.2", "type": "Box", "id": 2},
         {"op": "call", "object": "c4.2", "method": "keep", "id": 3})
    copy = Scene("lab")
    assert replay(copy, [*lines, left_line("c4")]) == (4, 0)
    assert list(copy.nodes) == ["c4.2"]


def test_a_line_cut_short_or_made_by_hand_does_no_more_than_its_client_could():
    scene = Scene("lab")
    session, lines = journaled(scene, "c4")
    send(session, {"op": "create", "object": "c4.1", "type": "Robot", "id": 1})
    hostile = [
        applied_line("c9", False, {"op": "delete", "object": "c4.1"}),  # not c9's
        applied_line("c9", False, {"op": "create", "object": "c4.7", "type": "Box"}),
        applied_line("c9", False, {"op": "launch", "object": "c4.1"}),
        b'{"client": "demo", "message": {"op": "delete", "object": "c4.1"}}',
        b'{"client": "c9", "message": 7}', b"[1, 2]", b"\xff\xfe", b'{"client": "c4", "mes',
    ]
    copy = Scene("lab")
    assert replay(copy, lines + hostile) == (1, len(hostile))
    assert list(copy.nodes) == ["c4.1"]
