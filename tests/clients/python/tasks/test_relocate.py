"""``relocate`` against the real server: the object brought to a target, MyoSuite's rule."""

import pytest

from virtual_prosthetics.tasks import relocate
from virtual_prosthetics.tasks.controller import PHASES, baseline
from virtual_prosthetics.tasks.hands import hand_source
from virtual_prosthetics.tasks.observation import Angles
from virtual_prosthetics.tasks.trial import TaskHand

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first


def test_the_baseline_brings_the_ball_and_the_cube_to_the_target_place_and_turn(scene):
    # the finding: no relocate task (MyoSuite: < 25 mm, < 0.262 rad, held > 5 steps)
    result = relocate.relocate(scene, TaskHand(hand_source("edged", scene)), 1, seed=3)
    assert result["task"] == "relocate" and result["criteria"]["positionM"] == 0.025
    for line in result["results"]:
        [trial] = line["each"]
        assert (line["successes"], line["drops"]) == (1, 0), line
        # closing rolled the object: the wrist turned it back to the target's turn
        assert trial["nearestM"] < 0.025 and trial["leastTurnRad"] < 0.262
        assert trial["stepsWithin"] > 5
    assert scene.read(lambda mirror: len(mirror.nodes)) == 0  # every trial cleaned away


def test_a_hand_that_lets_go_on_the_way_drops_and_fails(scene):
    def lets_go(grip):
        scripted = baseline(grip)

        def control(seen):
            if seen.t > PHASES.holding + 0.2:  # on the way to the target
                return Angles(seen.grip.angles({i: 0.0 for i in range(len(seen.grip.digits))}))
            return scripted(seen)
        return control

    result = relocate.relocate(scene, TaskHand(hand_source("edged", scene)), 1, seed=3,
                               patterns=("spherical",), controller=lets_go)
    [line] = result["results"]
    assert (line["successes"], line["drops"]) == (0, 1), line
