"""A robot as a URDF (zipped with its meshes): each hand's loads back into PyBullet with every
part where the server has it, with its limits, torques, inertials and mesh files."""

import io
import random
import zipfile
import xml.etree.ElementTree as ET

import numpy as np
import pybullet
import pytest
import trimesh
from scipy.spatial.transform import Rotation

from server.core.model.hands import AnthroHand, EdgedHand, RoundHand
from server.core.model.motor import MotorZ
from server.core.model.parts import Ball, Box
from server.core.model.robot import Robot
from server.core.protocol.robot_files import file_names, robot_urdf


HANDS = [EdgedHand, RoundHand, AnthroHand]


def posed(robot, position=(1, 2, 3), seed=7):
    """A robot turned and moved off the origin, every motor at a random angle in its range."""
    robot.set_position(position)
    robot.set_rotation(0.3, -0.5, 1.1)
    draw = random.Random(seed)
    for motor in robot.get_motors():
        motor.set_angle(draw.uniform(max(motor.min, -1.2), min(motor.max, 1.2)))
    return robot


def _posed(scene, kind):
    """A hand of ``kind``, posed, its parts placed."""
    hand = posed(kind(scene, "h", True))
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
