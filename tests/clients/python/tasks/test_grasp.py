"""``grasp`` against the real server: its set-up, its results and a user's controller."""

import json

import pytest

import virtual_prosthetics as vp
from virtual_prosthetics.tasks import grasp
from virtual_prosthetics.tasks.__main__ import main

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first


@pytest.mark.parametrize("hand", ["edged", "round", "anthro"])
def test_the_baseline_lifts_and_holds_the_ball_and_the_cube_and_leaves_the_scene_as_it_was(
        scene, hand):
    result = grasp.grasp(scene, hand, 1, seed=3, patterns=["spherical", "tripod"])
    assert result["task"] == "grasp" and result["hand"] == hand and result["seed"] == 3
    lines = result["results"]
    assert [(line["grip"], line["object"], line["weight"]) for line in lines] == \
        [("spherical", "sphere", "light"), ("spherical", "sphere", "heavy"),
         ("tripod", "cube", "light"), ("tripod", "cube", "heavy")]
    for line in lines:
        assert (line["trials"], line["successes"], line["successRate"]) == (1, 1, 1.0), line
        assert line["peakForceN"] > 0  # the hand pressed on the object during the hold
        assert line["slip"] < 0.05 * 0.04  # under 5 % of the object's size
    assert vp.get_physics()["mode"] == "dynamic"
    assert vp.get_physics()["unit"] == pytest.approx(result["unit"])  # a human hand's size
    assert scene.read(lambda mirror: len(mirror.nodes)) == 0  # every trial cleaned away


def test_a_controller_that_never_closes_the_hand_lifts_nothing(scene):
    def open_hand(grip):
        baseline = grasp.baseline(grip)

        def control(trial, t):
            baseline(trial, t)
            trial.hand.flex_fingers(0)  # the user's controller: the same path, hand open
        return control

    result = grasp.grasp(scene, "edged", 2, seed=3, patterns=["spherical"], controller=open_hand)
    assert [line["successes"] for line in result["results"]] == [0, 0]


def test_the_same_seed_draws_the_same_trials():
    import random
    assert grasp.draws(random.Random(5), 4) == grasp.draws(random.Random(5), 4)
    masses = [m for m, _ in grasp.draws(random.Random(5), 200)]
    assert min(masses) >= 0.5 and max(masses) <= 1.5 and max(masses) - min(masses) > 0.8


def test_the_command_line_prints_json_and_refuses_unknown_grips(server, scene_name, capsys):
    assert main(["grasp", "--url", server.ws, "--scene", scene_name, "--trials", "1",
                 "--grips", "tip"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["task"] == "grasp" and [l["grip"] for l in printed["results"]] == ["tip", "tip"]
    with pytest.raises(SystemExit) as refused:
        main(["grasp", "--url", server.ws, "--scene", scene_name, "--grips", "claw"])
    assert "unknown grip claw" in str(refused.value) and "spherical" in str(refused.value)
    with pytest.raises(SystemExit):
        main(["grasp", "--url", server.ws, "--trials", "0"])
    assert "at least 1" in capsys.readouterr().err
