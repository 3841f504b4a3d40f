"""MJCF robots read through MuJoCo's compiler: includes, default classes, degrees, meshdir,
couplings from equalities and tendons; every file the model names inside the upload."""

import math

import mujoco
import pytest

from server.core.kit.limits import DEFAULT
from server.core.physics.mjcf_reading import read_mjcf
from server.core.physics.robot_archive import open_archive
from server.core.kit.errors import BadAsset, Forbidden
from tests import hand_files
from tests.hand_files import mjcf_files, mjcf_zip, zipped


def read(data):
    return read_mjcf(open_archive(data, None, DEFAULT), DEFAULT, lambda glb: "x.glb")


def compiled():
    files = {path[len("hand/"):]: (data.encode() if isinstance(data, str) else data)
             for path, data in mjcf_files().items()}
    return mujoco.MjModel.from_xml_string(files.pop("scene.xml").decode(), files)


def test_the_mjcf_hand_reads_with_its_classes_units_and_couplings():
    robot, model = read(mjcf_zip()), compiled()
    assert (robot.name, robot.source) == ("mjcf_hand", "mjcf")
    motors = {joint.name: joint for joint in robot.motors()}
    assert len(motors) == model.njnt == 10
    knuckle = motors["index_knuckle"]
    assert (knuckle.lower, knuckle.upper) == pytest.approx(tuple(math.radians(d) for d in hand_files.MJCF_LIMITS_DEG))
    assert motors["middle_spread"].axis == (0.0, 1.0, 0.0) and knuckle.axis == (1.0, 0.0, 0.0)
    names = [link.name for link in robot.links]
    assert names[0] == "palm" and "middle_proximal_middle_spread" in names  # two hinges, two links
    palm = robot.links[0]
    assert palm.mass == pytest.approx(model.body("palm").mass[0])
    assert len(palm.hull) == 8  # the collision box only: the visual box (group 2) does not collide
    tip = robot.links[names.index("index_distal")]
    assert tip.hull is not None and tip.mesh == "x.glb"
    assert {(c.follower, c.leader, c.ratio, c.offset) for c in robot.couplings} == {
        ("index_distal_joint", "index_middle_joint", *hand_files.MJCF_EQUALITY),
        ("thumb_distal_joint", "thumb_middle_joint", 1.0, 0.0)}


def test_files_the_model_names_must_be_inside_the_upload():
    for change, refusal, words in [
            (lambda f: f.update({"hand/parts/hand.xml": f["hand/parts/hand.xml"].replace(
                "<worldbody>", '<worldbody><include file="/etc/hostname"/>')}), Forbidden, "relative paths"),
            (lambda f: f.update({"hand/scene.xml": f["hand/scene.xml"].replace('meshdir="meshes"', 'meshdir="../../x"')}),
             Forbidden, "leaves the upload"),
            (lambda f: f.pop("hand/meshes/tip.stl"), BadAsset, "'hand/meshes/tip.stl' is not in the upload"),
            (lambda f: f.update({"hand/parts/hand.xml": f["hand/parts/hand.xml"].replace(
                '<joint name="index_knuckle"/>', '<joint name="index_knuckle" type="ball"/>')}),
             BadAsset, "joint 'index_knuckle' is ball: only hinge"),
            (lambda f: f.update({"hand/scene.xml": f["hand/scene.xml"].replace('<mesh name="tip"', '<mesh name="tip" scale="a b"')}),
             BadAsset, "does not compile")]:
        files = mjcf_files()
        change(files)
        with pytest.raises(refusal, match=words):
            read(zipped(files))


def test_a_slide_joint_is_read_as_a_prismatic_one_in_metres():
    files = mjcf_files()
    pad = ('<body name="pad" pos="0 -0.05 0.02"><joint name="pad_slide" type="slide" axis="0 0 2" '
           'range="0 0.02"/><geom type="box" size=".01 .01 .01" mass="0.01"/></body>')
    files["hand/parts/hand.xml"] = files["hand/parts/hand.xml"].replace("</body></worldbody>", pad + "</body></worldbody>")
    robot = read(zipped(files))
    slide = next(joint for joint in robot.motors() if joint.name == "pad_slide")
    assert (slide.kind, slide.axis) == ("prismatic", (0.0, 0.0, 1.0))
    assert (slide.lower, slide.upper) == pytest.approx((0.0, 0.02))  # metres, not turned to radians


def test_a_folder_named_from_above_the_models_is_read_while_it_stays_in_the_upload():
    # Adroit's model names its meshes "../Adroit/resources/meshes/…" from its own folder
    files = mjcf_files()
    files["common/meshes/tip.stl"] = files.pop("hand/meshes/tip.stl")
    files["hand/scene.xml"] = files["hand/scene.xml"].replace('meshdir="meshes"', 'meshdir="../common/meshes"')
    robot, model = read(zipped(files)), compiled()
    tip = next(link for link in robot.links if link.name == "index_distal")
    assert tip.hull is not None and len(robot.motors()) == model.njnt


def test_two_different_files_of_one_name_are_refused_naming_both():
    # MuJoCo finds a model's files by their names alone: it would give one for the other
    files = mjcf_files()
    files["hand/parts/tip.stl"] = hand_files.tip_stl() + b" "
    files["hand/scene.xml"] = files["hand/scene.xml"].replace(
        '<mesh name="tip" file="tip.stl"/>', '<mesh name="tip" file="tip.stl"/><mesh name="tip2" file="../parts/tip.stl"/>')
    with pytest.raises(BadAsset, match="'hand/meshes/tip.stl' and 'hand/parts/tip.stl' are different files of one name"):
        read(zipped(files))


def test_two_bodies_under_the_world_are_refused_naming_them():
    two = """<mujoco model="m"><worldbody><body name="a"><geom size=".1"/></body>
             <body name="b"><geom size=".1"/></body></worldbody></mujoco>"""
    with pytest.raises(BadAsset, match="2: a, b"):
        read(two.encode())
