"""The scene's camera: set, reported in the next frame and in snapshots, undone with its request."""

import pytest

from server.core.kit.errors import OutOfRange


def test_camera_changes_are_reported(scene):
    scene.set_camera_position((1, 2, 3))
    [frame] = scene.tick(0.1)
    assert frame["camera"] == {"position": [1, 2, 3], "target": [0, 1, 0]}


def test_a_camera_nobody_placed_says_so_until_a_script_places_it(scene):
    """Viewers frame what the scene holds while the camera is nobody's choice."""
    assert scene.snapshot()["camera"] == {"position": [4, 4, 7], "target": [0, 1, 0],
                                          "placed": False}
    scene.set_camera_target((0, 2, 0))
    assert "placed" not in scene.snapshot()["camera"]
    scene.camera.reset()
    assert scene.snapshot()["camera"]["placed"] is False


def test_a_failed_request_puts_the_camera_back(scene):
    scene.set_camera_target((0, 2, 0))
    scene.tick(0.1)
    with pytest.raises(OutOfRange), scene.journal.transaction():
        scene.set_camera_position((5, 5, 5))
        raise OutOfRange("late failure")
    kept = {"position": [4, 4, 7], "target": [0, 2, 0]}  # placed: by the target
    assert scene.snapshot()["camera"] == kept
    [frame] = scene.tick(0.1)  # viewers that saw nothing of it are told the same
    assert frame.get("camera", kept) == kept
