"""URDF robots read: links, joints, axes, limits, names, couplings and masses as the file
says them, meshes inside the upload only, and what cannot be a hand refused by name."""

import math

import numpy as np
import pytest

from server.core.kit.limits import DEFAULT
from server.core.physics.robot_archive import open_archive
from server.core.physics.urdf_reading import read_urdf
from server.core.kit.errors import BadAsset, Forbidden, LimitExceeded
from tests import hand_files
from tests.hand_files import hand_urdf, hand_zip, zipped


def read(data, limits=DEFAULT, kept=None):
    kept = {} if kept is None else kept
    return read_urdf(open_archive(data, None, limits), limits,
                     lambda glb: kept.setdefault(f"{len(kept)}.glb", glb) and f"{len(kept) - 1}.glb")


def test_the_hand_reads_as_its_file_says():
    kept = {}
    robot = read(hand_zip(), kept=kept)
    assert (robot.name, robot.source) == ("test_hand", "urdf")
    names = [link.name for link in robot.links]
    assert names[0] == "palm" and len(names) == 2 + 3 * len(hand_files.DIGITS)
    assert [j.name for j in robot.motors()] == hand_files.motor_names()
    for joint in robot.motors():
        assert (joint.kind, joint.axis, (joint.lower, joint.upper), joint.effort) == \
            ("revolute", hand_files.AXIS, hand_files.LIMITS, 0.5)
    palm, mount = robot.links[0], robot.links[1]
    assert (palm.mass, palm.inertia, palm.friction) == (hand_files.PALM_MASS, (4e-4, 3e-4, 6e-4), 0.9)
    assert mount.joint.kind == "fixed" and mount.hull is None and mount.mesh is not None
    assert mount.joint.origin[0] == (0.0, -0.05, 0.02)
    corners = np.abs(np.asarray(palm.hull))  # the box's envelope: its eight corners
    assert len(palm.hull) == 8 and np.allclose(corners, np.asarray(hand_files.PALM) / 2)
    proximal = robot.links[names.index("index_proximal")]
    assert proximal.parent == 0 and proximal.centre == (0.0, 0.0, hand_files.SEGMENT / 2)
    assert robot.links[proximal.parent + names.index("index_middle") - 0].parent == names.index("index_proximal")
    assert {(c.follower, c.leader, c.ratio, c.offset) for c in robot.couplings} == {
        (f"{d}_{s}_joint", f"{d}_proximal_joint", *hand_files.MIMIC)
        for d in hand_files.DIGITS for s in ("middle", "distal")}
    assert len(kept) == len(robot.links)  # one GLB a drawn link


def test_a_links_glb_carries_its_colour_and_its_elements_placed():
    import trimesh
    kept = {}
    robot = read(hand_zip(), kept=kept)
    tip = next(link for link in robot.links if link.name == "index_distal")
    drawn = trimesh.load(trimesh.util.wrap_as_stream(kept[tip.mesh]), file_type="glb", force="mesh")
    colours = np.asarray(drawn.visual.vertex_colors)[:, :3] / 255
    assert np.allclose(colours, hand_files.TIP_COLOR[:3], atol=0.01)
    assert drawn.bounds[1][2] == pytest.approx(hand_files.SEGMENT, abs=1e-6)  # the STL's own frame


@pytest.mark.parametrize("joint_type", ["floating", "planar"])
def test_joints_a_hand_cannot_have_here_are_refused_by_name(joint_type):
    extra = f"""<link name="loose"/><joint name="free_one" type="{joint_type}">
      <parent link="palm"/><child link="loose"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>"""
    with pytest.raises(BadAsset, match=f"joint 'free_one' is {joint_type}"):
        read(zipped({"h.urdf": hand_urdf("tip.stl", extra), "tip.stl": hand_files.tip_stl()}))


def test_broken_trees_entities_and_missing_meshes_are_refused_naming_them():
    with pytest.raises(BadAsset, match="one root link.*2: palm, lonely"):
        read(hand_urdf("tip.stl", '<link name="lonely"/>').encode())
    entity = b'<?xml version="1.0"?><!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]>'
    with pytest.raises(BadAsset, match="external entity"):  # never read
        read(entity + b'<robot name="&x;"><link name="a"/></robot>')
    with pytest.raises(BadAsset, match="has a DOCTYPE"):
        read(entity + b'<robot name="r"><link name="a"/><!-- &x; --></robot>')
    with pytest.raises(BadAsset, match="not well-formed XML"):
        read(b"<robot name='x'><link></robot>")
    with pytest.raises(BadAsset, match="mesh 'package://handpkg/meshes/tip.stl' is not in the upload"):
        read(hand_urdf().encode())
    with pytest.raises(Forbidden):
        read(zipped({"h.urdf": hand_urdf("../../secret.stl")}))


def test_a_robots_triangles_are_counted_against_its_limit():
    with pytest.raises(LimitExceeded) as refused:
        read(hand_zip(), DEFAULT.with_values(["robotTriangles=100"]))
    assert refused.value.details["limit"] == "robotTriangles"


def test_a_continuous_joint_turns_without_limits():
    urdf = hand_urdf("tip.stl").replace('name="thumb_proximal_joint" type="revolute"',
                                        'name="thumb_proximal_joint" type="continuous"')
    robot = read(zipped({"h.urdf": urdf, "tip.stl": hand_files.tip_stl()}))
    thumb = robot.motors()[0]
    assert (thumb.name, thumb.lower, thumb.upper) == ("thumb_proximal_joint", -math.inf, math.inf)


def test_a_description_that_declares_an_xml_version_no_parser_knows_is_read_as_utf8():
    data = zipped({"h.urdf": '<?xml version="0.0" ?>\n' + hand_urdf("tip.stl"), "tip.stl": hand_files.tip_stl()})
    assert read(data).name == "test_hand"  # PyBullet's own minitaur.urdf says version 0.0
