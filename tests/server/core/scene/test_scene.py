"""The scene: ids, transactions, the change feed, ticks, contacts and readings in frames."""


import pytest

from server.core.model.motor import MotorZ
from server.core.model.parts import Ball, Box, EdgedFinger, EdgedPalm
from server.core.model.sensor import Sensor
from server.core.model.robot import Robot
from server.core.kit.errors import DuplicateId, OutOfRange, StorageFailure


def frame_of(messages):
    return next(m for m in messages if m["op"] == "frame")


def test_ids_are_unique_and_never_reused(scene):
    box = Box(scene, "a")
    with pytest.raises(DuplicateId):
        Box(scene, "a")
    scene.delete(box)
    with pytest.raises(DuplicateId):
        Box(scene, "a")


def test_failed_transaction_undoes_everything(scene):
    robot = Robot(scene, "r")
    motor = MotorZ(scene, "m", -1, 1)
    robot.attach_chain(motor)
    motor.set_angle(0.5)
    with pytest.raises(OutOfRange), scene.journal.transaction():
        motor.set_angle(-0.25)
        extra = EdgedFinger(scene, "f")
        extra.attach_to_slot(motor)
        robot.set_position((1, 2, 3))
        scene.delete(motor)
        raise OutOfRange("late failure")
    assert motor.angle == 0.5 and robot.position == (0, 0, 0)
    assert "f" not in scene.nodes and scene.nodes["m"] is motor
    assert motor.parent is robot and motor.slots[0].children == []
    assert robot.get_motors() == [motor]


def test_set_angles_turns_all_motors_at_once_and_undoes_them_together(scene):
    robot = Robot(scene, "r")
    motors = [MotorZ(scene, f"m{i}", -1, 1) for i in range(3)]
    finger = EdgedFinger(scene, "f")
    robot.attach_chain(*motors, finger)
    scene.tick(0.1)
    tip_before = finger.world_pose()
    with pytest.raises(OutOfRange), scene.journal.transaction():
        robot.set_angles(0.5, None, 9)  # None keeps one, 9 is clamped to 1
        assert robot.get_angles() == [0.5, 0.0, 1.0] and finger.world_pose() != tip_before
        raise OutOfRange("late failure")
    assert robot.get_angles() == [0.0, 0.0, 0.0] and finger.world_pose() == tip_before
    robot.set_angles(0.5, 0, 0.25)
    frame = frame_of(scene.tick(0.1))
    assert frame["angles"] == {"r": [0.5, 0.0, 0.25]}  # all the robot's, in motor order
    assert scene.bodies.physics.parts.pose("f")[0] == pytest.approx(finger.world_pose()[0])


def test_tick_reports_added_frame_removed_in_order(scene):
    first = scene.tick(0.5)
    assert first == [{"op": "frame", "seq": 1, "time": 0.5}]
    robot = Robot(scene, "r")
    motor = MotorZ(scene, "m")
    robot.attach_chain(motor)
    added, frame = scene.tick(0.5)
    assert added["op"] == "added" and [n["id"] for n in added["nodes"]] == ["r", "m", "m/s0"]
    assert frame == {"op": "frame", "seq": 2, "time": 1.0}  # new nodes come whole
    motor.set_angle(0.3)
    robot.set_position((1, 0, 0))
    [frame] = scene.tick(0.5)
    assert frame["angles"] == {"r": [0.3]}
    assert frame["poses"] == {"r": [1, 0, 0, 0, 0, 0, 1]}
    scene.delete(motor)
    frame, removed = scene.tick(0.5)
    assert removed == {"op": "removed", "seq": 4, "ids": sorted(["m", "m/s0"])} or \
        set(removed["ids"]) == {"m", "m/s0"}
    assert frame["updates"] == {"r": {"children": [], "motors": []}}


def test_reattaching_reports_both_parents_children(scene):
    a, b, part = Box(scene, "a"), Box(scene, "b"), Box(scene, "p")
    part.attach_to_slot(a)
    scene.tick(0.1)
    part.attach_to_slot(b)
    [frame] = scene.tick(0.1)
    assert frame["updates"] == {"a": {"children": []}, "b": {"children": ["p"]},
                                "p": {"parent": "b"}}


def test_delta_of_a_recording_holds_only_its_changes(scene):
    motor = MotorZ(scene, "m")
    scene.tick(0.1)
    with scene.recording() as changes:
        motor.set_angle(1.0)
    assert scene.delta(changes) == {"angles": {"m": 1.0}}


def test_snapshot_lists_parents_before_children_and_encodes_infinity(scene):
    robot = Robot(scene, "r")
    robot.attach_chain(MotorZ(scene, "m"))
    snapshot = scene.snapshot()
    ids = [n["id"] for n in snapshot["nodes"]]
    assert ids == ["r", "m", "m/s0"]
    motor = snapshot["nodes"][1]
    assert (motor["min"], motor["max"]) == ("-Infinity", "Infinity")



def test_a_snapshot_gives_the_forces_the_frames_told_so_a_newcomer_sees_a_resting_load(scene):
    box = Box(scene, "b", 1, 1, 1)
    box.set_position((0, 0.6, 0))
    assert "forces" not in scene.snapshot()  # kinematic mode: nothing presses
    scene.set_physics("dynamic")
    told: dict[str, float] = {}
    for _ in range(240):  # it lands and lies still: the frames stop telling its force
        told |= scene.tick(1 / 60)[-1].get("forces", {})
    assert "forces" not in scene.tick(1 / 60)[-1]
    forces = scene.snapshot()["forces"]
    assert forces == {k: v for k, v in told.items() if v} and forces["b"] > 0


def test_a_snapshot_gives_the_watched_sensors_readings_of_the_world_now(scene):
    """After a restore the snapshot is all a client has of the new world: a watched
    sensor's reading comes with it, not only with the next tick's frame."""
    Box(scene, "roof", 4, 0.1, 4).set_position((0, 3, 0))
    sensor = Sensor(scene, "s")
    assert "sensors" not in scene.snapshot()  # watched by nobody
    scene.watches.add("s", "c1")
    assert scene.snapshot()["sensors"]["s"]["distance"] == pytest.approx(2.95, abs=0.01)
    sensor.set_position((0, 1, 0))
    assert scene.snapshot()["sensors"]["s"]["distance"] == pytest.approx(1.95, abs=0.01)


@pytest.mark.parametrize("make", [
    lambda scene: EdgedFinger(scene, "flat", 1, 0, 0.3),   # no thickness
    lambda scene: EdgedFinger(scene, "flat", 1, 0.3, 0),   # no width
    lambda scene: EdgedFinger(scene, "flat", 0, 0, 0),     # a point
    lambda scene: EdgedPalm(scene, "flat", True, 1.4, 1.4, 0),
    lambda scene: Box(scene, "flat", 1, 0, 1),
    lambda scene: Ball(scene, "flat", 0),
])
def test_parts_without_volume_are_still_met_by_rays_and_contacts(scene, make):
    part = make(scene)
    part.set_position((0, 1, 0))
    Box(scene, "floor", 4, 0.1, 4).set_position((0, 1.05, 0))  # covers the part's origin
    sensor = Sensor(scene, "s")
    sensor.set_position((0, 0.5, 0))  # looking up at the part's origin from below
    distance = sensor.sense_distance()
    scene.tick(0.1)
    assert scene.failures == 0
    assert distance <= 0.5 + 1e-6  # the part (or, for a point, the floor at its origin)
    assert "floor" in scene.bodies.touching(part)


def test_a_client_that_leaves_takes_what_it_made_and_did_not_keep(scene):
    robot = Robot(scene, "c1.1")
    robot.attach_chain(MotorZ(scene, "c1.2", -1, 1), EdgedFinger(scene, "c1.3"))
    Box(scene, "c1.4").keep()
    Ball(scene, "c2.1")
    assert scene.remove_client("c1") == ["c1.3", "c1.2", "c1.1"]   # newest first
    assert sorted(scene.nodes) == ["c1.4", "c2.1"]
    assert "c1" not in scene.ids.wire()   # its ids are never handed out again


def test_a_scene_run_outside_a_server_says_it_keeps_no_recordings(scene):
    for call in (lambda: scene.start_recording("c1"), scene.stop_recording):
        with pytest.raises(StorageFailure) as refused:
            call()
        assert "outside a server" in refused.value.message


def _resting_ball(scene):
    """A dynamic scene with a ball come to rest on the ground: a still world."""
    scene.set_physics("dynamic")
    with scene.journal.transaction():
        Ball(scene, "ball", 0.5).set_position((0.0, 0.25, 0.0))
    for _ in range(120):
        scene.tick(1 / 60)


def _put_up_in_a_still_world(stand):
    """A ball at rest, then, paused, put 3 up beside a new batch of 300 balls, with a
    stand (``stand``) between those requests and the steps or none; where all end."""
    from server.core.scene.scene import Scene
    scene = Scene(f"stands-{stand}")
    try:
        scene.pause("script")
        _resting_ball(scene)
        with scene.journal.transaction():
            scene.nodes["ball"].set_position((0.0, 3.0, 0.0))
            for i in range(300):
                Ball(scene, f"b{i}", 0.2).set_position((5.0, 0.1 + 0.2 * i, 0.0))
        if stand:
            assert frame_of(scene.stand())["time"] == pytest.approx(2.0)  # the clock stood
        for _ in range(30):
            scene.tick(1 / 60)
        return [node.position for node in scene.nodes.values() if isinstance(node, Ball)]
    finally:
        scene.close()


def test_a_paused_scenes_stands_change_nothing_so_a_script_ends_the_same_at_any_load():
    """A paused scene stands (a frame of no time) when the wall clock says, between a
    script's requests as the machine's speed has it. A stand that built and sensed the
    world made the same seeded grasp hold 5 of 8 on a loaded machine and 7 on an idle
    one, and a ball put up high in a still world hung there for good."""
    stood, not_stood = _put_up_in_a_still_world(True), _put_up_in_a_still_world(False)
    assert stood[0][1] < 2.0  # the ball fell
    assert stood == not_stood


def test_a_stand_sends_what_changed_and_leaves_the_world_unbuilt_until_the_step(scene):
    scene.set_physics("dynamic")
    scene.pause("script")
    with scene.journal.transaction():
        Ball(scene, "b", 0.2).set_position((0, 2, 0))
    messages = scene.stand()
    added = next(m for m in messages if m["op"] == "added")
    assert frame_of(messages)["time"] == 0.0 and [n["id"] for n in added["nodes"]] == ["b"]
    assert "b" not in scene.bodies.physics
    scene.tick(1 / 60)
    assert "b" in scene.bodies.physics and scene.nodes["b"].position[1] < 2


def test_a_tick_too_short_for_a_step_leaves_a_change_to_the_next(scene):
    # a still world, a ball put up, a tick shorter than a physics step (a late tick's
    # catch-up): the contacts it read cleared the change, and the ball hung in the air
    _resting_ball(scene)
    with scene.journal.transaction():
        scene.nodes["ball"].set_position((0, 3, 0))
    scene.tick(0.001)
    for _ in range(10):
        scene.tick(1 / 60)
    assert scene.nodes["ball"].position[1] < 2.9
