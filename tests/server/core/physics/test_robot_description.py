"""A robot read from a file, kept as JSON: the same description back, bit for bit, and a
kept file that was changed by hand refused naming what is wrong."""

import json

import pytest

from server.core.kit.limits import DEFAULT
from server.core.physics.robot_archive import open_archive
from server.core.physics.robot_description import RobotDescription
from server.core.physics.urdf_reading import read_urdf
from server.core.kit.errors import BadAsset
from tests.hand_files import hand_zip


@pytest.fixture(scope="module")
def robot():
    return read_urdf(open_archive(hand_zip(), None, DEFAULT), DEFAULT, lambda glb: "x.glb")


def test_a_description_comes_back_from_its_json_exactly(robot):
    data = robot.to_json()
    assert RobotDescription.from_json(data) == robot
    assert RobotDescription.from_json(data).to_json() == data  # the same bytes: the same hash
    assert json.loads(data)["links"][2]["joint"]["lower"] == 0.0


@pytest.mark.parametrize("change, message", [
    (lambda d: d["links"][2].update(parent=5), "parent must come before it"),
    (lambda d: d["links"][2]["joint"].update(kind="ball"), "of kind 'ball'"),
    (lambda d: d["links"][2]["joint"].update(lower=2.0, upper=1.0), "lower limit above"),
    (lambda d: d["links"][0].update(mass=-1), "non-negative|positive"),
    (lambda d: d["links"][0].update(hull=[[1e9, 0, 0]]), "within"),
    (lambda d: d["couplings"][0].update(leader="camera_fix"), "no turning joint 'camera_fix'"),
    (lambda d: d.update(version=7), "not a robot description"),
    (lambda d: d["links"][1].update(name=""), "a name must be"),
])
def test_a_kept_description_changed_by_hand_is_refused(robot, change, message):
    document = json.loads(robot.to_json())
    change(document)
    with pytest.raises(BadAsset, match=message):
        RobotDescription.from_json(json.dumps(document).encode())
