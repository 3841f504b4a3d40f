"""Imported robots are ordinary robots: links are parts where the file's kinematics put
them (checked against yourdfpy's forward kinematics), joints are motors named and limited
as the file says, mimic joints follow, and the physics builds and drives them."""

import io

import numpy as np
import pytest
import yourdfpy

from server.core.kit.limits import DEFAULT
from server.core.kit.math3d import to_matrix
from server.core.model.hands import EdgedHand
from server.core.model.imported import ImportedRobot, RobotLink
from server.core.physics.assets import AssetLibrary
from server.core.physics.robot_archive import open_archive
from server.core.physics.urdf_reading import read_urdf
from server.core.scene.scene import Scene
from server.core.kit.errors import BadAsset, UnknownAsset
from server.web.storage.upload_folder import UploadFolder
from tests import hand_files
from tests.hand_files import hand_zip


@pytest.fixture
def library(tmp_path):
    return AssetLibrary(uploads=tmp_path)


@pytest.fixture
def hand_file(library):
    robot = read_urdf(open_archive(hand_zip(), None, DEFAULT), DEFAULT,
                      lambda glb: UploadFolder(library).store(glb, DEFAULT)["name"])
    return UploadFolder(library).store_robot(robot, DEFAULT)["name"]


@pytest.fixture
def lab(library):
    scene = Scene("lab", assets=library)
    yield scene
    scene.close()


def file_poses(angles, extra=""):
    """Each link's pose in the robot's frame as yourdfpy computes it from the URDF."""
    urdf = yourdfpy.URDF.load(io.StringIO(hand_files.hand_urdf(extra=extra)), build_scene_graph=True,
                              load_meshes=False)
    urdf.update_cfg(angles)
    return {link: urdf.get_transform(link, urdf.base_link) for link in urdf.link_map}


def test_links_sit_where_the_files_kinematics_put_them_with_mimic_joints_following(lab, hand_file):
    robot = ImportedRobot(lab, "c1.1", hand_file)
    motors = robot.get_motors()
    assert [m.name for m in motors] == hand_files.motor_names()
    assert all((m.min, m.max) == hand_files.LIMITS for m in motors)
    robot.set_angles(0.9, 0.1, 0.1, 0.4, None, None, 1.3)  # followers' own angles are ignored
    leaders = {"thumb_proximal_joint": 0.9, "index_proximal_joint": 0.4, "middle_proximal_joint": 1.3}
    ratio, offset = hand_files.MIMIC
    assert robot.get_angles() == pytest.approx(
        [a if k == 0 else min(ratio * a + offset, 1.6) for a in leaders.values() for k in range(3)])
    expected = file_poses(leaders)
    links = [p for p in robot.get_parts() if isinstance(p, RobotLink)]
    assert sorted(p.name for p in links) == sorted(expected)
    for part in links:
        position, quaternion = part.world_pose()
        matrix = expected[part.name]  # (in metres: the robot is scaled to the scene's unit)
        assert np.allclose(np.asarray(position) * lab.physics.unit, matrix[:3, 3], atol=1e-9), part.name
        assert np.allclose(np.asarray(to_matrix(quaternion)), matrix[:3, :3], atol=1e-9), part.name


def test_an_imported_robot_is_drawn_enveloped_weighed_and_driven_in_dynamic_mode(lab, hand_file):
    robot = ImportedRobot(lab, "c1.1", hand_file)
    robot.set_position((0.0, 6.0, 0.0))  # 0.33 m up (the scene's unit: 1.0 hands human-sized)
    palm, mount = robot.get_parts()[0], robot.get_parts()[1]
    assert palm.geometry()["kind"] == "mesh" and len(palm.geometry()["points"]) == 8
    assert (mount.physical, "points" in mount.geometry()) == (False, False)  # drawn, not solid
    assert (palm.get_mass(), palm.friction) == (hand_files.PALM_MASS, 0.9)
    lab.set_physics("dynamic")
    robot.set_angles(1.0, None, None, 0.5)
    for _ in range(120):
        lab.tick(1 / 60)
    angles = robot.get_angles()
    assert angles[0] == pytest.approx(1.0, abs=0.02) and angles[3] == pytest.approx(0.5, abs=0.02)
    assert angles[1] == pytest.approx(0.85, abs=0.03)  # a follower driven with its leader
    assert palm.world_pose()[0] == pytest.approx((0.0, 6.0, 0.0), abs=1e-3)  # held at its mount
    assert [m.get_max_torque() for m in robot.get_motors()] == [0.5] * 9  # the file's effort


def test_a_robot_file_that_is_missing_or_not_a_robot_makes_nothing(lab, library, hand_file):
    with pytest.raises(UnknownAsset):
        ImportedRobot(lab, "c1.1", "0123456789abcdef0123456789abcdef.robot")
    with pytest.raises(BadAsset, match="is not a robot file"):
        ImportedRobot(lab, "c1.1", "round-palm.glb")
    assert "c1.1" not in lab.nodes


def test_an_mjcf_hands_bodies_sit_where_mujoco_puts_them(lab, library):
    import mujoco

    from server.core.kit.math3d import compose, rotate

    def inverse(pose):
        (px, py, pz), (x, y, z, w) = pose
        turn = (-x, -y, -z, w)
        return tuple(-c for c in rotate(turn, (px, py, pz))), turn
    from server.core.physics.mjcf_reading import read_mjcf
    from tests.server.core.physics.test_mjcf_reading import compiled
    robot_file = UploadFolder(library).store_robot(read_mjcf(open_archive(hand_files.mjcf_zip(), None, DEFAULT), DEFAULT,
                                               lambda glb: UploadFolder(library).store(glb, DEFAULT)["name"]), DEFAULT)["name"]
    robot = ImportedRobot(lab, "c1.1", robot_file)
    by_name = {m.name: m for m in robot.get_motors()}
    for name, angle in {"thumb_knuckle": 0.4, "thumb_middle_joint": 0.6, "index_middle_joint": 0.9,
                        "middle_spread": -0.2, "middle_knuckle": 1.1, "middle_middle_joint": 0.3}.items():
        by_name[name].set_angle(angle)
    assert by_name["thumb_distal_joint"].angle == 0.6  # the tendon's second joint follows
    assert by_name["index_distal_joint"].angle == pytest.approx(0.7 * 0.9 + 0.02)
    model = compiled()
    data = mujoco.MjData(model)
    for motor in robot.get_motors():
        data.qpos[model.joint(motor.name).qposadr[0]] = motor.angle
    mujoco.mj_kinematics(model, data)

    def pose(body):  # a body's pose relative to the palm's, as MuJoCo has it
        w, x, y, z = data.xquat[model.body(body).id]
        return tuple(data.xpos[model.body(body).id]), (x, y, z, w)
    palm = pose("palm")
    links = {p.name: p for p in robot.get_parts() if isinstance(p, RobotLink)}
    for body in ("thumb_distal", "index_distal", "middle_proximal", "middle_distal"):
        position, quaternion = compose(inverse(palm), pose(body))
        anchor = -0.005 if body == "middle_proximal" else 0.0  # its link sits at its joint
        unit = lab.physics.unit  # the robot is in scene units of this many metres
        ours = compose(links[body].world_pose(), ((0.0, 0.0, -anchor / unit), (0.0, 0.0, 0.0, 1.0)))
        assert np.allclose(np.asarray(ours[0]) * unit, position, atol=1e-9), body
        assert np.allclose(np.asarray(to_matrix(ours[1])), np.asarray(to_matrix(quaternion)), atol=1e-9), body


def test_beside_a_1_0_hand_an_imported_hand_keeps_its_metres(lab, hand_file):
    edged = EdgedHand(lab, "c1.h", True)
    edged.flex_fingers(0)
    edged.spread_fingers(0)
    robot = ImportedRobot(lab, "c1.1", hand_file)
    robot.set_position((4.0, 0.0, 0.0))
    lab.tick(1 / 60)

    def extent(parts):  # metres along y, the fingers' way for both hands
        boxes = [lab.bodies.physics.parts.aabb(p.id) for p in parts if p.physical]
        return (max(b[1][1] for b in boxes) - min(b[0][1] for b in boxes)) * lab.physics.unit
    palm = next(p for p in robot.get_parts() if isinstance(p, RobotLink) and p.name == "palm")
    assert extent([palm]) == pytest.approx(hand_files.PALM[1], abs=0.002)  # 10 cm, as its file says
    assert extent(edged.get_parts()) == pytest.approx(0.19, abs=0.01)  # a human hand's


@pytest.fixture
def jaws_file(library):
    return hand_files.stored_hand(library, hand_files.JAWS)


def test_prismatic_joints_become_sliders_in_scene_units_where_the_files_kinematics_put_them(lab, jaws_file):
    robot = ImportedRobot(lab, "c1.1", jaws_file)
    jaw_a, jaw_b = robot.get_motors()[-2:]
    unit = lab.physics.unit
    assert (jaw_a.type_name, jaw_a.name, jaw_b.name) == ("Slider", "jaw_a_slide", "jaw_b_slide")
    # limits in scene units: the file's metres at the robot's size (it keeps its metres)
    assert (jaw_a.min * unit, jaw_a.max * unit) == pytest.approx(hand_files.SLIDE_LIMITS)
    assert jaw_a.get_max_torque() == hand_files.SLIDE_EFFORT  # newtons
    jaw_a.set_angle(0.02 / unit)  # 2 cm; the mirrored jaw follows (mimic, offset 1 mm)
    assert jaw_b.angle * unit == pytest.approx(0.021)
    expected = file_poses({"jaw_a_slide": 0.02, "jaw_b_slide": 0.021}, hand_files.JAWS)
    for part in robot.get_parts():
        if isinstance(part, RobotLink) and part.name.startswith("jaw"):
            position, quaternion = part.world_pose()
            matrix = expected[part.name]
            assert np.allclose(np.asarray(position) * unit, matrix[:3, 3], atol=1e-9), part.name
            assert np.allclose(np.asarray(to_matrix(quaternion)), matrix[:3, :3], atol=1e-9), part.name


def test_sliders_drive_their_jaws_in_dynamic_mode_and_the_palm_holds(lab, jaws_file):
    robot = ImportedRobot(lab, "c1.1", jaws_file)
    robot.set_position((0.0, 6.0, 0.0))
    lab.set_physics("dynamic")
    jaw_a, jaw_b = robot.get_motors()[-2:]
    unit = lab.physics.unit
    jaw_a.set_angle(0.025 / unit)
    for _ in range(120):
        lab.tick(1 / 60)
    assert jaw_a.get_angle() * unit == pytest.approx(0.025, abs=5e-4)  # read from the physics
    assert jaw_b.get_angle() * unit == pytest.approx(0.026, abs=5e-4)  # its follower with it
    palm = robot.get_parts()[0]
    assert palm.world_pose()[0] == pytest.approx((0.0, 6.0, 0.0), abs=1e-3)
