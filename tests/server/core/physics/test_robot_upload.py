"""An uploaded robot read and kept: the answer says what the file holds (its motors in
order, their limits, which follow which and how), the description is kept once under its
hash with its links' meshes, and a file that does not read keeps nothing."""

import pytest

from server.core.kit.errors import BadAsset, VPError
from server.core.kit.limits import DEFAULT
from server.core.physics.assets import AssetLibrary
from server.core.physics.robot_upload import store_robot_upload
from server.web.storage.upload_folder import UploadFolder
from tests.hand_files import LIMITS, MIMIC, hand_urdf, hand_zip, motor_names, zipped


@pytest.fixture
def library(tmp_path):
    return AssetLibrary(uploads=tmp_path)


def test_the_answer_says_what_the_file_holds_and_the_robot_reads_back(library):
    report = store_robot_upload(UploadFolder(library), hand_zip(), None, DEFAULT)
    assert (report["source"], report["description"]) == ("urdf", "handpkg/urdf/hand.urdf")
    assert [m["name"] for m in report["motors"]] == motor_names()
    assert all((m["min"], m["max"]) == LIMITS for m in report["motors"])
    follows = {m["name"]: m["follows"] for m in report["motors"]}
    assert follows["index_proximal_joint"] is None
    assert follows["index_distal_joint"] == ["index_proximal_joint", *MIMIC]
    robot = library.robot(report["file"])  # as a scene's process will read it
    assert robot.name == report["name"] and len(robot.links) == report["links"]
    kept = library.uploaded_names()
    assert report["file"] in kept and any(name.endswith(".glb") for name in kept)
    again = store_robot_upload(UploadFolder(library), hand_zip(), None, DEFAULT)
    assert again == report and library.uploaded_names() == kept  # the same file: kept once


@pytest.mark.parametrize("data, file", [
    (b"not a robot", None),
    (zipped({"hand.urdf": hand_urdf().replace("</robot>", "<joint name='x'/></robot>")}), None),
    (zipped({"a.urdf": hand_urdf(), "b.urdf": hand_urdf()}), None),
])
def test_a_file_that_does_not_read_is_refused_and_keeps_no_description(library, data, file):
    with pytest.raises(VPError):
        store_robot_upload(UploadFolder(library), data, file, DEFAULT)
    assert not [name for name in library.uploaded_names() if name.endswith(".robot")]


def test_a_robot_whose_mesh_is_missing_names_it(library):
    with pytest.raises(BadAsset, match="tip.stl"):
        store_robot_upload(UploadFolder(library), zipped({"hand.urdf": hand_urdf()}), None, DEFAULT)
