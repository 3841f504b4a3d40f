"""A long task's progress bar on stderr: scene seconds of the total, the time left."""

from virtual_prosthetics.tasks import progress


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
