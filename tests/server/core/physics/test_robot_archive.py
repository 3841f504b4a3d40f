"""An uploaded robot's files: zips and bare files, which member is the description, and
mesh references that resolve inside the upload and nowhere else."""

import pytest

from server.core.kit.limits import DEFAULT
from server.core.physics.robot_archive import open_archive
from server.core.kit.errors import BadAsset, Forbidden, LimitExceeded, TooLarge
from tests.hand_files import hand_urdf, hand_zip, tip_stl, zipped


def test_a_ros_package_zip_finds_its_urdf_and_resolves_package_and_relative_paths():
    archive = open_archive(hand_zip(), None, DEFAULT)
    assert (archive.description, archive.format) == ("handpkg/urdf/hand.urdf", "urdf")
    assert archive.resolve("package://handpkg/meshes/tip.stl") == ("handpkg/meshes/tip.stl", tip_stl())
    assert archive.resolve("../meshes/tip.stl")[0] == "handpkg/meshes/tip.stl"
    assert archive.resolve("file://../meshes/tip.stl")[0] == "handpkg/meshes/tip.stl"


def test_a_package_found_from_the_upload_root_when_the_zip_is_the_package_itself():
    archive = open_archive(zipped({"hand.urdf": hand_urdf(), "meshes/tip.stl": b"x"}), None, DEFAULT)
    assert archive.resolve("package://somewhere_else/meshes/tip.stl")[0] == "meshes/tip.stl"


@pytest.mark.parametrize("reference, refusal", [
    ("../../../etc/passwd", Forbidden), ("../../etc/passwd", BadAsset), ("/etc/passwd", Forbidden), ("file:///etc/passwd", Forbidden),
    ("http://example.com/tip.stl", Forbidden), ("package://handpkg/../../../x", Forbidden),
    ("meshes\\tip.stl", Forbidden), ("../meshes/missing.stl", BadAsset)])
def test_references_that_leave_the_upload_or_are_not_in_it_are_refused(reference, refusal):
    archive = open_archive(hand_zip(), None, DEFAULT)
    with pytest.raises(refusal, match="upload|not allowed"):
        archive.resolve(reference)


def test_a_bare_urdf_or_mjcf_is_a_one_file_upload_and_anything_else_is_refused():
    assert open_archive(hand_urdf().encode(), None, DEFAULT).format == "urdf"
    mjcf = b'<?xml version="1.0"?>\n<!-- a hand --><mujoco model="m"><worldbody/></mujoco>'
    assert open_archive(mjcf, None, DEFAULT).format == "mjcf"
    with pytest.raises(BadAsset, match="neither a zip nor a URDF"):
        open_archive(b"solid cube\nendsolid", None, DEFAULT)
    with pytest.raises(BadAsset, match="names a file inside a zip"):
        open_archive(hand_urdf().encode(), "hand.urdf", DEFAULT)


def test_several_descriptions_need_file_and_a_zip_member_path_may_not_escape():
    two = zipped({"a.urdf": hand_urdf(), "b.urdf": hand_urdf()})
    with pytest.raises(BadAsset, match=r"several robot descriptions \(a.urdf, b.urdf\): name one with \?file="):
        open_archive(two, None, DEFAULT)
    assert open_archive(two, "b.urdf", DEFAULT).description == "b.urdf"
    with pytest.raises(BadAsset, match=r"\?file=c.urdf: the zip has no such file"):
        open_archive(two, "c.urdf", DEFAULT)
    with pytest.raises(Forbidden, match="leaves the upload"):
        open_archive(zipped({"../evil.urdf": hand_urdf()}), None, DEFAULT)
    main = b'<mujoco model="m"><include file="parts.xml"/><worldbody/></mujoco>'
    included = zipped({"hand/scene.xml": main, "hand/parts.xml": b"<mujoco><default/></mujoco>"})
    assert open_archive(included, None, DEFAULT).description == "hand/scene.xml"


def test_zip_limits_are_checked_before_anything_is_inflated():
    small = DEFAULT.with_values(["robotFiles=2", "robotBytes=5000"])
    with pytest.raises(LimitExceeded) as refused:
        open_archive(hand_zip(), None, small)
    assert refused.value.details["limit"] == "robotFiles"
    bomb = zipped({"hand.urdf": hand_urdf(), "big.stl": b"\0" * 100_000})
    with pytest.raises(TooLarge) as too_big:
        open_archive(bomb, None, DEFAULT.with_values(["robotBytes=50000"]))
    assert too_big.value.details == {"limit": "robotBytes", "value": 50000, "flag": "--limit robotBytes=N"}
    with pytest.raises(BadAsset, match="not a readable zip"):
        open_archive(b"PK\x03\x04garbage", None, DEFAULT)
