"""A robot as files other tools open: each hand's URDF loads back into PyBullet with every
part where the server has it, and its GLB opens in trimesh with the hand's bounds."""

import io
import random
import zipfile
import xml.etree.ElementTree as ET

import numpy as np
import pybullet
import pytest
import trimesh
from scipy.spatial.transform import Rotation

from server.core.physics.dynamics import DEFAULT_MAX_TORQUE
from server.core.model.hands import AnthroHand, EdgedHand, RoundHand
from server.core.model.motor import MotorZ, Slider
from server.core.model.parts import Ball, Box
from server.core.model.robot import Robot
from server.core.physics.assets import BUNDLED_DIR
from server.core.protocol.robot_files import file_names, robot_glb, robot_mjcf, robot_urdf
from server.core.kit.errors import UnknownObject
from server.web.storage.upload_folder import UploadFolder

HANDS = [EdgedHand, RoundHand, AnthroHand]


def _posed(scene, kind):
    """A hand turned and moved off the origin, every motor at a random angle in its range."""
    hand = kind(scene, "h", True)
    hand.set_position((1, 2, 3))
    hand.set_rotation(0.3, -0.5, 1.1)
    draw = random.Random(7)
    for motor in hand.get_motors():
        motor.set_angle(draw.uniform(max(motor.min, -1.2), min(motor.max, 1.2)))
    scene.tick(1 / 60)
    return hand


def _unzipped(data, folder):
    zipfile.ZipFile(io.BytesIO(data)).extractall(folder)
    return folder / "h" / "robot.urdf"


@pytest.mark.parametrize("kind", HANDS)
def test_a_hands_urdf_loads_into_pybullet_with_every_part_where_the_server_has_it(scene, kind, tmp_path):
    hand = _posed(scene, kind)
    urdf = _unzipped(robot_urdf(scene, "h"), tmp_path)
    client = pybullet.connect(pybullet.DIRECT)
    try:
        unit = scene.physics.unit  # the file is in metres
        body = pybullet.loadURDF(str(urdf), np.asarray(hand.position) * unit, hand.quaternion, useFixedBase=True,
                                 physicsClientId=client)
        links = {}
        named = {file_names(hand).get(m.id, m.id): m for m in hand.get_motors()}
        for j in range(pybullet.getNumJoints(body, physicsClientId=client)):
            info = pybullet.getJointInfo(body, j, physicsClientId=client)
            links[info[12].decode()] = j
            if info[2] == pybullet.JOINT_REVOLUTE:  # named by its motor
                pybullet.resetJointState(body, j, named[info[1].decode()].get_angle(),
                                         physicsClientId=client)
        placed = _visual_origins(urdf)
        parts = [p for p in hand.get_parts() if p.physical]
        assert set(placed) == {p.id for p in parts}
        for part in parts:
            state = pybullet.getLinkState(body, links[part.id], computeForwardKinematics=True,
                                          physicsClientId=client)
            offset, _ = placed[part.id]
            where = np.asarray(state[4]) + Rotation.from_quat(state[5]).apply(offset)
            assert where == pytest.approx(np.asarray(part.world_pose()[0]) * unit, abs=1e-6), part.id
    finally:
        pybullet.disconnect(client)


def _visual_origins(urdf):
    """Each link's visual origin, read as any URDF reader reads it."""
    found = {}
    for link in ET.parse(urdf).getroot().findall("link"):
        origin = link.find("visual/origin")
        if origin is not None:
            found[link.get("name")] = ([float(v) for v in origin.get("xyz").split()],
                                       [float(v) for v in origin.get("rpy").split()])
    return found


def test_the_urdf_has_limits_torques_inertials_and_mesh_files(scene, tmp_path):
    hand = EdgedHand(scene, "h", True)
    hand.get_motors()[3].set_max_torque(1234)
    urdf = _unzipped(robot_urdf(scene, "h"), tmp_path)
    robot = ET.parse(urdf).getroot()
    joints = {j.get("name"): j for j in robot.findall("joint") if j.get("type") != "fixed"}
    motors = hand.get_motors()
    names = file_names(hand)
    assert list(joints) == [names.get(m.id, m.id) for m in motors]  # every motor, in motor order
    assert "Thumb" in names.values() or any(m.name for m in motors) is False
    limit = joints[names.get(motors[3].id, motors[3].id)].find("limit")
    assert float(limit.get("effort")) == 1234
    assert (float(limit.get("lower")), float(limit.get("upper"))) == (motors[3].min, motors[3].max)
    for link in robot.findall("link"):
        assert float(link.find("inertial/mass").get("value")) > 0
        mesh = link.find("collision/geometry/mesh")
        if mesh is not None:  # a hull Bullet collides with, as a file beside the URDF
            hull = trimesh.load(urdf.parent / mesh.get("filename"))
            assert hull.is_watertight and hull.is_convex


def test_a_palm_weighs_its_volume_times_the_density_at_its_centre(scene, tmp_path):
    robot = Robot(scene, "h")
    box = Box(scene, "b", 2, 1, 0.5)
    box.attach_to_slot(robot)
    scene.set_physics("dynamic", {"density": 300, "unit": 0.1})  # a box of 20 × 10 × 5 cm
    link = [l for l in ET.parse(_unzipped(robot_urdf(scene, "h"), tmp_path)).getroot()
            .findall("link") if l.get("name") == "b"][0]
    mass = 0.2 * 0.1 * 0.05 * 300
    assert float(link.find("inertial/mass").get("value")) == pytest.approx(mass)
    assert float(link.find("inertial/inertia").get("ixx")) == pytest.approx(mass / 12 * (0.1 ** 2 + 0.05 ** 2))
    assert float(link.find("collision/geometry/box").get("size").split()[0]) == pytest.approx(0.2)


def test_an_unlimited_motor_is_a_continuous_joint(scene, tmp_path):
    robot = Robot(scene, "h")
    motor = MotorZ(scene, "m")
    motor.attach_to_slot(robot)
    Ball(scene, "b", 0.3).attach_to_slot(motor)
    robot_joints = ET.parse(_unzipped(robot_urdf(scene, "h"), tmp_path)).getroot().findall("joint")
    (joint,) = [j for j in robot_joints if j.get("name") == "m"]
    assert joint.get("type") == ("continuous" if motor.min == -np.inf else "revolute")


@pytest.mark.parametrize("kind", HANDS)
def test_a_hands_glb_opens_in_trimesh_with_the_hands_bounds(scene, kind):
    hand = _posed(scene, kind)
    opened = trimesh.load(io.BytesIO(robot_glb(scene, "h")), file_type="glb")
    parts = [p for p in hand.get_parts() if p.physical]
    assert set(opened.graph.nodes_geometry) == {p.id for p in parts}
    corners = np.concatenate([_drawn_corners(p) for p in parts])
    metres = np.array([corners.min(axis=0), corners.max(axis=0)]) * scene.physics.unit
    assert opened.bounds == pytest.approx(metres, abs=1e-5)
    assert 0.15 < np.ptp(opened.bounds, axis=0).max() < 0.25  # a human hand's size


def _drawn_corners(part):
    """The points a viewer draws a part through, in the world: a hull's corners, or its
    mesh file's vertices placed as the part places them."""
    geometry = part.geometry()
    if geometry["kind"] == "mesh":
        mesh = trimesh.load(BUNDLED_DIR / geometry["url"].rsplit("/", 1)[1], force="mesh")
        points = np.asarray(mesh.vertices) * ([-1, 1, 1] if geometry["mirror"] else 1) + geometry["offset"]
    else:
        points = np.asarray(geometry["points"])
    position, quaternion = part.world_pose()
    return Rotation.from_quat(quaternion).apply(points) + position


def test_the_glb_colours_parts_as_the_viewer_does(scene):
    hand = RoundHand(scene, "h", True)  # its files' blue recoloured grey: [0.3, 0.3, 0.3]
    robot = Robot(scene, "r")
    Box(scene, "b", 1, 1, 1, "steelblue").attach_to_slot(robot)
    palm = trimesh.load(io.BytesIO(robot_glb(scene, "h")), file_type="glb").geometry[hand.get_parts()[0].id]
    colours = {tuple(c) for c in np.asarray(palm.visual.vertex_colors)[:, :3].tolist()}
    assert (76, 76, 76) in colours and (0, 54, 255) not in colours  # 0.3 × 255
    box = trimesh.load(io.BytesIO(robot_glb(scene, "r")), file_type="glb").geometry["b"]
    # CSS colours are sRGB; glTF's (and three.js's) are linear: steelblue is (70, 130, 180)
    assert box.visual.material.name == "steelblue"
    assert tuple(box.visual.material.baseColorFactor[:3]) == (16, 57, 116)


def test_a_robots_glb_is_a_node_per_link_with_local_transforms(scene):
    hand = _posed(scene, EdgedHand)
    opened = trimesh.load(io.BytesIO(robot_glb(scene, "h")), file_type="glb")
    parents = opened.graph.transforms.parents
    palm, spread = hand.get_parts()[0], hand.get_motors()[0]
    finger = next(p for p in hand.get_parts() if p.type_name == "EdgedFinger")  # the thumb's first
    # a link per part, and one where two motors meet (the spread's), each below its parent
    assert [finger.id, parents[finger.id], parents[parents[finger.id]], parents[palm.id]] == \
        [finger.id, f"{spread.id}.link", palm.id, "h"]
    assert parents["h"] == opened.graph.base_frame
    local, _ = opened.graph.get(finger.id, f"{spread.id}.link")
    world, _ = opened.graph.get(finger.id)
    assert world[:3, 3] == pytest.approx(np.asarray(finger.world_pose()[0]) * scene.physics.unit, abs=1e-9)
    assert not np.allclose(local, world)  # local transforms, not world poses


def test_a_robot_without_parts_is_a_glb_that_draws_nothing(scene):
    Robot(scene, "r")
    data = robot_glb(scene, "r")  # trimesh's export refused it: a 400 'internal' over REST
    assert data[:4] == b"glTF"
    loaded = trimesh.load(io.BytesIO(data), file_type="glb")
    assert isinstance(loaded, trimesh.Scene) and not loaded.geometry


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
    robot.set_position((0.1, 0.2, 0.3))
    robot.set_rotation(0.3, -0.5, 1.1)
    draw = random.Random(3)
    for motor in robot.get_motors():
        motor.set_angle(draw.uniform(max(motor.min, -1.2), min(motor.max, 1.2)))
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


def test_the_mjcf_compiles_in_mujoco_with_an_actuator_per_leading_motor(tmp_path):
    import mujoco
    from server.core.model.imported import ImportedRobot
    from server.core.physics.assets import AssetLibrary
    from server.core.scene.scene import Scene
    from tests.hand_files import motor_names, stored_hand
    library = AssetLibrary(uploads=tmp_path / "uploads")
    (tmp_path / "uploads").mkdir()
    scene = Scene("mjcf", assets=library)
    ImportedRobot(scene, "h", stored_hand(library))
    zipfile.ZipFile(io.BytesIO(robot_mjcf(scene, "h"))).extractall(tmp_path)
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "h" / "robot.xml"))
    joints = [model.joint(j).name for j in range(model.njnt)]
    assert joints == motor_names()
    leaders = [name for name in joints if name.endswith("proximal_joint")]
    assert [model.actuator(a).name for a in range(model.nu)] == leaders
    assert model.neq == len(joints) - len(leaders)  # each follower, an equality on its leader
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


@pytest.mark.parametrize("kind", HANDS)
def test_a_1_0_hands_mjcf_holds_its_aim_in_mujoco(scene, kind, tmp_path):
    import mujoco
    kind(scene, "h", True)
    zipfile.ZipFile(io.BytesIO(robot_mjcf(scene, "h"))).extractall(tmp_path)
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "h" / "robot.xml"))
    data = mujoco.MjData(model)
    data.ctrl[:] = 0.8  # every actuator's aim (a joint's limits may stop it short)
    for _ in range(1500):  # 3 s of MuJoCo's own steps
        mujoco.mj_step(model, data)
    joints = [model.actuator_trnid[a, 0] for a in range(model.nu)]
    aims = np.clip(0.8, model.jnt_range[joints, 0], model.jnt_range[joints, 1])
    reached = data.qpos[[model.jnt_qposadr[j] for j in joints]]
    assert np.all(np.isfinite(data.qpos)) and np.abs(reached - aims).max() < 0.06  # not flung


def test_a_sliders_glb_node_sits_where_it_slid(scene):
    robot, slider = Robot(scene, "r"), Slider(scene, "s", [0.0, 0.6, 0.8], 0, 2, 0)
    Box(scene, "b", 0.5, 0.5, 0.5).attach_to_slot(slider)
    robot.attach_chain(slider)
    robot.set_position((1.0, 2.0, 0.0))
    slider.set_angle(1.5)
    opened = trimesh.load(io.BytesIO(robot_glb(scene, "r")), file_type="glb")
    world, _ = opened.graph.get("b")
    assert world[:3, 3] == pytest.approx(np.asarray((1.0, 2.9, 1.2)) * scene.physics.unit, abs=1e-9)
