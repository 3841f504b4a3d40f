"""A long task's progress: a bar on stderr (scene seconds of the total, the time left) and
the scene's caption in every viewer."""

import time

import virtual_prosthetics as vp
from tests.conftest import WAIT_SECONDS
from virtual_prosthetics.tasks import progress
from virtual_prosthetics.tasks.trial import drive


def test_a_bar_counts_scene_seconds_to_its_total_and_an_inner_task_adds_to_it(capsys):
    with progress.shown(3.0, "grasp mine"):
        progress.advance(1.0)
        with progress.shown(10.0, "inner"):  # no bar of its own
            progress.advance(1.5)
        progress.advance(1.0)  # a tick past the planned total stays at it
    err = capsys.readouterr().err
    assert "grasp mine: 100%" in err and "3/3 scene-s" in err and "inner" not in err
    progress.advance(1.0)  # no bar open: nothing shown, nothing raised
    assert capsys.readouterr().err == ""


def test_a_task_tells_the_scene_its_name_time_and_score_and_viewers_see_it(server, scene,
                                                                          scene_name):
    """Found: nothing on screen said the trial, the score or the progress."""
    viewer = vp.Session(server.ws, scene_name, role="viewer")
    try:
        with progress.shown(2.0, "grasp mine"):
            progress.tell("spherical · trials 1-10 of 20")
            drive(scene, 0.5, lambda t: None)
            seen = viewer_caption(viewer, "0.5 of 2")
        assert seen == "grasp mine · 0.5 of 2 scene-s\nspherical · trials 1-10 of 20"
    finally:
        viewer.close()


def viewer_caption(viewer, part: str) -> str:
    deadline = time.monotonic() + WAIT_SECONDS
    while part not in (caption := viewer.read(lambda mirror: mirror.caption)):
        assert time.monotonic() < deadline, caption
        time.sleep(0.02)
    return caption
