"""The scene's caption: set, reported in the next frame, in snapshots and documents, undone
with its request."""

import pytest

from server.core.protocol.scene_document import export_scene, import_scene
from server.core.kit.errors import OutOfRange


def test_a_caption_goes_out_once_in_a_frame_and_stays_in_snapshots(scene):
    assert "caption" not in scene.snapshot()
    scene.set_caption("grasp · trial 1 of 10\nheld 0 of 0")
    [frame] = scene.tick(0.1)
    assert frame["caption"] == "grasp · trial 1 of 10\nheld 0 of 0"
    [frame] = scene.tick(0.1)
    assert "caption" not in frame
    assert scene.snapshot()["caption"] == "grasp · trial 1 of 10\nheld 0 of 0"
    scene.set_caption("")  # hidden: viewers are told so
    [frame] = scene.tick(0.1)
    assert frame["caption"] == "" and "caption" not in scene.snapshot()


def test_a_failed_request_puts_the_caption_back(scene):
    scene.set_caption("before")
    scene.tick(0.1)
    with pytest.raises(OutOfRange), scene.journal.transaction():
        scene.set_caption("after")
        raise OutOfRange("late failure")
    assert scene.caption.text == "before"


def test_a_document_keeps_the_caption_and_a_camera_nobody_placed(scene):
    scene.set_caption("box and blocks · 12 blocks")
    document = export_scene(scene)
    assert document["caption"] == "box and blocks · 12 blocks"
    assert document["camera"]["placed"] is False
    scene.set_caption("")
    scene.set_camera_position((9, 9, 9))
    with scene.journal.transaction():
        import_scene(scene, document)
    assert scene.caption.text == "box and blocks · 12 blocks"
    assert scene.snapshot()["camera"] == {"position": [4, 4, 7], "target": [0, 1, 0],
                                          "placed": False}
