"""``grasp`` against the real server: its set-up, its results and a user's controller."""

import json

import pytest

import virtual_prosthetics as vp
from tests import hand_files
from virtual_prosthetics.tasks import grasp
from virtual_prosthetics.tasks.__main__ import main
from virtual_prosthetics.tasks.hands import hand_source
from virtual_prosthetics.tasks.observation import Angles
from virtual_prosthetics.tasks.trial import TaskHand


def _hand(scene, spec):
    return TaskHand(hand_source(spec, scene))

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first


# Closed by their grip maps, not by tables naming them, the 1.0 hands still hold the ball
# and the cube, but for one: the anthro hand's derived thumb passes beside the 4 cm cube
# (0 of 10 at seed 3; 10 of 10 with the table it had). Strict: it fails once it holds.
ANTHRO_CUBE = pytest.mark.xfail(strict=True, reason="issue 46: the anthro hand's derived grip "
                                "misses the tripod's cube")


@pytest.mark.parametrize("hand, pattern, item", [
    ("edged", "spherical", "sphere"), ("edged", "tripod", "cube"),
    ("round", "spherical", "sphere"), ("round", "tripod", "cube"),
    ("anthro", "spherical", "sphere"), pytest.param("anthro", "tripod", "cube", marks=ANTHRO_CUBE)])
def test_the_baseline_lifts_and_holds_the_ball_and_the_cube_and_leaves_the_scene_as_it_was(
        server, scene, scene_name, hand, pattern, item):
    # two trials of each: a held light ball is chaotic (the anthro hand's held 13 and 14 of
    # 20 at seed 11 before and after the hands' mounts were made to hold where they are
    # put; which two of three drop moves with any change of a hair)
    result = grasp.grasp(scene, _hand(scene, hand), 2, seed=3, patterns=[pattern])
    figures = server.get("/api/metrics")["scenes"][scene_name]
    # found: each step's reads sent its orders ahead and waited for their answer (1 424
    # requests for 756 ticks): a step is one request, with the tick
    assert figures["requests"] < 1.2 * figures["ticks"], figures
    assert result["task"] == "grasp" and result["hand"] == hand and result["seed"] == 3
    lines = result["results"]
    assert [(line["grip"], line["object"], line["weight"]) for line in lines] == \
        [(pattern, item, "light"), (pattern, item, "heavy")]
    for line in lines:
        assert line["trials"] == 2 and line["successes"] >= 1, line
        assert line["peakForceN"] > 0  # the hand pressed on the object during the hold
        held = [trial for trial in line["each"] if trial["held"]]
        assert all(trial["slip"] < 0.05 * 0.04 for trial in held), line  # under 5 % of its size
    assert vp.get_physics()["mode"] == "dynamic"
    assert vp.get_physics()["unit"] == pytest.approx(result["unit"])  # a human hand's size
    assert scene.read(lambda mirror: len(mirror.nodes)) == 0  # every trial cleaned away


def test_a_gripper_no_table_names_holds_the_ball_and_the_cube(scene):
    # the finding: "--hand mine" was an invalid choice; the tasks knew three hands by name
    hands = _hand(scene, "tests.clients.python.tasks.gripper:three_digits")
    result = grasp.grasp(scene, hands, 2, seed=5, patterns=["spherical", "tripod"])
    assert result["hand"] == "tests.clients.python.tasks.gripper:three_digits"
    # of 8 (light and heavy, ball and cube, twice each): 6 (gripper.py's servos held 37 of
    # 40 over 5 trials each at seeds 5 and 7, 34 before robots' mounts held their bases
    # as hard to turn as their loads; which trials drop is chaotic)
    held = [line["successes"] for line in result["results"]]
    assert sum(held) >= 6, result["results"]


def test_a_controller_that_never_closes_the_hand_lifts_nothing(scene):
    def open_hand(grip):
        def control(seen):  # the user's controller: the hand open all the way
            return Angles(seen.grip.angles({i: 0.0 for i in range(len(seen.grip.digits))}))
        return control

    result = grasp.grasp(scene, _hand(scene, "edged"), 1, seed=3, patterns=["spherical"],
                         controller=open_hand)
    assert [line["successes"] for line in result["results"]] == [0, 0]


def test_the_same_seed_draws_the_same_trials():
    import random
    assert grasp.draws(random.Random(5), 4) == grasp.draws(random.Random(5), 4)
    masses = [m for m, _ in grasp.draws(random.Random(5), 200)]
    assert min(masses) >= 0.5 and max(masses) <= 1.5 and max(masses) - min(masses) > 0.8


def test_the_command_line_evaluates_a_robot_file_with_a_grip_map_of_its_own(server, scene_name, capsys,
                                                                            tmp_path):
    path = tmp_path / "hand.zip"
    path.write_bytes(hand_files.hand_zip())
    grip_map = tmp_path / "grip.json"  # the fingers only, by their joints' names
    grip_map.write_text(json.dumps({"digits": [
        {"opposes": True, "motors": [{"name": "thumb_proximal_joint", "open": 0, "closed": 1.6}]},
        {"motors": [{"name": "index_proximal_joint", "open": 0, "closed": 1.6}]}]}))
    assert main(["grasp", "--url", server.ws, "--scene", scene_name, "--trials", "1",
                 "--grips", "spherical", "--hand", str(path), "--grip-map", str(grip_map)]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["hand"] == "hand" and [l["weight"] for l in printed["results"]] == ["light", "heavy"]


def test_the_command_line_prints_json_and_refuses_unknown_grips(server, scene_name, capsys):
    assert main(["grasp", "--url", server.ws, "--scene", scene_name, "--trials", "1",
                 "--grips", "tip"]) == 0
    captured = capsys.readouterr()
    printed = json.loads(captured.out)
    assert printed["task"] == "grasp" and [l["grip"] for l in printed["results"]] == ["tip", "tip"]
    # the finding: minutes with no output; a bar of scene seconds with the time left, on stderr
    assert "grasp edged: 100%" in captured.err and f"{2 * grasp.PHASES.end:.0f}/" in captured.err
    with pytest.raises(SystemExit) as refused:
        main(["grasp", "--url", server.ws, "--scene", scene_name, "--grips", "claw"])
    assert "unknown grip claw" in str(refused.value) and "spherical" in str(refused.value)
    with pytest.raises(SystemExit):
        main(["grasp", "--url", server.ws, "--trials", "0"])
    assert "at least 1" in capsys.readouterr().err
