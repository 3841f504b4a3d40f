"""A robot's files by its id: an unknown one refused by name, a robot made again from its
own URDF or MJCF is the same robot, and a 1.0 hand exports at a human hand's size."""

import io
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import trimesh

from server.core.physics.dynamics import DEFAULT_MAX_TORQUE
from server.core.model.hands import AnthroHand, EdgedHand
from server.core.model.parts import Ball
from server.core.protocol.robot_files import file_names, robot_glb, robot_mjcf, robot_urdf
from server.core.kit.errors import UnknownObject
from server.web.storage.upload_folder import UploadFolder
from tests.server.core.physics.test_urdf_file import HANDS, _unzipped, posed


def test_an_unknown_robot_is_refused_by_name(scene):
    Ball(scene, "b", 1)
    for name in ("nobody", "b"):
        with pytest.raises(UnknownObject) as refused:
            robot_urdf(scene, name)
        assert name in refused.value.message


def _reimported(scene, robot, library, form):
    """The robot made again from its own URDF or MJCF export, at the same pose and angles."""
    from server.core.kit.limits import DEFAULT
    from server.core.model.imported import ImportedRobot
    from server.core.physics.mjcf_reading import read_mjcf
    from server.core.physics.robot_archive import open_archive
    from server.core.physics.urdf_reading import read_urdf
    read, export = (read_urdf, robot_urdf) if form == "urdf" else (read_mjcf, robot_mjcf)
    description = read(open_archive(export(scene, robot.id), None, DEFAULT), DEFAULT,
                       lambda glb: UploadFolder(library).store(glb, DEFAULT)["name"])
    again = ImportedRobot(scene, "again", UploadFolder(library).store_robot(description, DEFAULT)["name"])
    again.set_position(robot.position)
    again.set_quaternion(robot.quaternion)
    names = file_names(robot)
    angles = {names.get(m.id, m.id): m.angle for m in robot.get_motors()}
    for motor in again.get_motors():
        if motor.following is None:
            motor.set_angle(angles[motor.name])
    return again, names


@pytest.mark.parametrize("form", ["urdf", "mjcf"])
@pytest.mark.parametrize("kind", ["imported", "jaws", EdgedHand, AnthroHand])
def test_a_robot_made_again_from_its_urdf_or_mjcf_is_the_same_robot(kind, form, tmp_path):
    from server.core.physics.assets import AssetLibrary
    from server.core.scene.scene import Scene
    from tests.hand_files import JAWS, stored_hand
    from server.core.model.imported import ImportedRobot
    library = AssetLibrary(uploads=tmp_path)
    scene = Scene("round-trip", assets=library)
    if isinstance(kind, str):  # the test hand, with sliding jaws (prismatic joints) or without
        robot = ImportedRobot(scene, "h", stored_hand(library, JAWS if kind == "jaws" else ""))
    else:
        robot = kind(scene, "h", True)
    posed(robot, (0.1, 0.2, 0.3), seed=3)
    again, names = _reimported(scene, robot, library, form)
    parts = {p.name: p for p in again.get_parts() if getattr(p, "name", None)}
    for part in robot.get_parts():
        if not part.physical:
            continue
        twin = parts[names.get(part.id, part.id)]
        (p, q), (p2, q2) = part.world_pose(), twin.world_pose()
        assert np.allclose(p, p2, atol=1e-6) and abs(abs(np.dot(q, q2)) - 1) < 1e-9, part.id
    motors = {m.name: m for m in again.get_motors()}
    for motor in robot.get_motors():
        twin = motors[names.get(motor.id, motor.id)]
        assert (twin.min, twin.max) == pytest.approx((motor.min, motor.max), abs=1e-6)
        assert twin.angle == pytest.approx(motor.angle, abs=1e-6)
        assert (twin.following is None) == (motor.following is None)
        assert twin.type_name == ("Slider" if motor.slides else "Motor")
    scene.close()


@pytest.mark.parametrize("kind", HANDS)
def test_a_1_0_hand_exports_at_a_human_hands_size_weight_and_torque(scene, kind, tmp_path):
    hand = kind(scene, "h", True)
    hand.flex_fingers(0)
    hand.spread_fingers(0)
    urdf = ET.parse(_unzipped(robot_urdf(scene, "h"), tmp_path)).getroot()
    mass = sum(float(m.get("value")) for m in urdf.iter("mass"))
    efforts = {float(limit.get("effort")) for limit in urdf.iter("limit")}
    opened = trimesh.load(io.BytesIO(robot_glb(scene, "h")), file_type="glb")
    length = np.ptp(opened.bounds, axis=0).max()
    assert 0.15 < length < 0.25 and 0.2 < mass < 1.0  # metres and kilograms
    assert efforts == {DEFAULT_MAX_TORQUE}  # N·m, a small servo's
