"""The change feed: the tick's set and a request's recording each see what they should."""

from server.core.model.motor import MotorZ
from server.core.model.parts import Box
from server.core.model.robot import Robot


def test_a_recording_sees_only_its_block_and_the_tick_sees_everything(scene):
    box = Box(scene, "b")
    with scene.recording() as changes:
        box.set_position((1, 0, 0))
        scene.warn("careful")
    box.set_position((2, 0, 0))
    assert list(changes.poses) == ["b"] and changes.warnings == ["careful"]
    pending = scene.feed.pending
    assert list(pending.born) == ["b"] and pending.warnings == []  # nobody to warn in a tick


def test_moving_a_motor_into_a_robot_changes_its_motor_list_and_a_box_does_not(scene):
    robot = Robot(scene, "r")
    scene.tick(0.1)
    with scene.recording() as with_motor:
        robot.attach_chain(MotorZ(scene, "m"))
    with scene.recording() as with_box:
        Box(scene, "b").attach_to_slot(scene.nodes["m"])
    assert with_motor.updates["r"] == {"children", "motors"}
    assert "r" not in with_box.updates and with_box.updates["m/s0"] == {"children"}
