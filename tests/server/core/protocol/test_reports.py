"""Read-only views of a scene for REST: what a hand looks like from outside."""

from server.core.model.hands import EdgedHand
from server.core.model.motor import MotorZ
from server.core.model.parts import Ball
from server.core.protocol import reports


def test_a_robots_report_lists_its_parts_motors_in_order_and_pose(scene):
    hand = EdgedHand(scene, "c1.1", False)
    hand.set_position((1, 2, 3))
    Ball(scene, "c1.2")
    hand.flex_finger(1, 0.5)
    assert [r.id for r in reports.robots(scene)] == ["c1.1"]
    summary = reports.scene_summary(scene)
    assert summary["robots"] == 1 and summary["objects"] == len(scene.nodes)
    assert summary["pausedBy"] is None
    scene.pause("c1")
    assert reports.scene_summary(scene)["pausedBy"] == "c1"  # why its clock stands
    report = reports.robot_report(hand)
    assert report["owner"] == "c1" and report["position"] == [1, 2, 3]
    assert [m["index"] for m in report["motors"]] == list(range(20))
    assert [m["id"] for m in report["motors"]] == hand.motors
    assert [m["angle"] for m in report["motors"][5:8]] == [-0.5] * 3
    palm = report["parts"][0]
    assert palm["parent"] == "c1.1" and palm["world"]["position"] == [1, 2, 3]


def test_a_motors_limits_travel_as_the_wire_writes_them(scene):
    motor = MotorZ(scene, "m")
    assert reports.motor_report(motor, 0)["min"] == "-Infinity"
