"""A scene's clock held by a script: pause, step, resume, and what undoes or ends them."""

import pytest

from server.core.scene.scene import Scene
from server.core.kit.errors import Forbidden, NotPaused, OutOfRange


@pytest.fixture
def scene():
    made = Scene("clock")
    yield made
    made.close()


def test_steps_count_only_while_paused_and_are_taken_once(scene):
    with pytest.raises(NotPaused, match=r"pause\(\) first"):
        scene.step(2)
    scene.pause("c1")
    scene.step(2)
    scene.step(3)
    assert scene.clock.paused and scene.clock.take() == 5 and scene.clock.take() == 0
    scene.step(4)
    scene.resume()
    assert not scene.clock.paused and scene.clock.take() == 0  # a resumed scene owes nothing


def test_a_failed_batch_undoes_its_pause_and_its_steps(scene):
    with pytest.raises(RuntimeError), scene.journal.transaction():
        scene.pause("c1")
        scene.step(5)
        raise RuntimeError("a later op of the batch failed")
    assert not scene.clock.paused and scene.clock.owed == 0


def test_the_pause_ends_when_the_client_that_paused_leaves_for_good(scene):
    scene.pause("c1")
    scene.remove_client("c2")
    assert scene.clock.paused_by == "c1"
    scene.remove_client("c1")
    assert not scene.clock.paused


def test_the_steps_of_one_message_are_bounded_however_they_are_batched(scene):
    scene.pause("c1")
    scene.step(40)
    with pytest.raises(OutOfRange, match="at most 60 ticks; 40 asked already, 21 more"):
        scene.step(21)
    scene.step(20)
    assert scene.clock.take() == 60


def test_one_client_holds_the_clock_at_a_time(scene):
    """Two task runs in one scene each paused it and stepped the other's ticks, laying
    their trials over each other; the second is now refused, naming the holder."""
    scene.pause("c1")
    with pytest.raises(Forbidden, match="held by c1") as refused:
        scene.pause("c2")
    assert refused.value.details["owner"] == "c1" and scene.clock.paused_by == "c1"
    scene.pause("c1")  # (pausing again is no change)
    scene.resume()
    scene.pause("c2")
    assert scene.clock.paused_by == "c2"
