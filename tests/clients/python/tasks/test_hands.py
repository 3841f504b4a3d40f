"""Which hand a task evaluates: a 1.0 hand, a robot file, a function, a robot in the scene."""

from __future__ import annotations

import pytest

import virtual_prosthetics as vp
from tests import hand_files
from virtual_prosthetics.tasks.hands import hand_source, robot_source


def test_a_10_hand_is_made_by_name(scene):
    source = hand_source("round", scene)
    assert source.name == "round" and source.owned
    assert isinstance(source.make(scene), vp.RoundHand)


def test_a_robot_file_is_uploaded_once_and_made_as_often_as_wanted(scene, tmp_path):
    path = tmp_path / "hand.zip"
    path.write_bytes(hand_files.hand_zip())
    source = hand_source(str(path), scene)
    first, second = source.make(scene), source.make(scene)
    assert source.name == "hand" and first.id != second.id
    assert isinstance(first, vp.ImportedRobot) and len(second.get_motors()) == 9


def test_a_function_builds_the_hand_in_the_session_it_is_given(scene):
    source = hand_source("tests.clients.python.tasks.gripper:three_digits", scene)
    robot = source.make(scene)
    assert [m.get_name() for m in robot.get_motors()][:2] == ["thumb base", "thumb middle"]


@pytest.mark.parametrize("spec, said", [
    ("claw", "not one of anthro, edged, round, not a robot file"),
    ("no_such_module:make", "cannot import 'no_such_module'"),
    ("tests.clients.python.tasks.gripper:nothing", "has no 'nothing'"),
])
def test_what_names_no_hand_is_refused_saying_what_a_hand_may_be(scene, spec, said):
    with pytest.raises(ValueError, match=said):
        hand_source(spec, scene)


def test_a_function_that_returns_no_robot_is_refused_when_it_runs(scene):
    source = hand_source("tests.clients.python.tasks.test_hands:_not_a_robot", scene)
    with pytest.raises(ValueError, match="not the robot it built"):
        source.make(scene)


def _not_a_robot(session):
    return vp.Box(scene=session)


def test_a_robot_in_the_scene_is_evaluated_where_it_is_and_kept(scene):
    robot = vp.EdgedHand()
    scene.sync()
    source = robot_source(robot.id, scene)
    assert source.make(scene) is robot and not source.owned
    with pytest.raises(ValueError, match="no robot of that id"):
        robot_source("nobody.1", scene)
