"""A robot as an MJCF model (zipped with its meshes): it compiles in MuJoCo, an actuator per
leading motor and an equality per follower, and a 1.0 hand holds its aim there."""

import io
import zipfile

import numpy as np
import pytest

from server.core.protocol.robot_files import robot_mjcf
from tests.server.core.physics.test_urdf_file import HANDS


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
