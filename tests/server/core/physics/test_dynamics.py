"""Dynamic mode's Bullet side (in a scene: its own tests use every part)."""

import math

import pytest

from server.core.model.motor import MotorZ
from server.core.model.parts import Ball, Box, EdgedFinger
from server.core.model.robot import Robot
from server.core.model.sensor import Sensor
from server.core.physics import dynamics
from server.core.physics.dynamics import DEFAULT_MAX_TORQUE
from server.core.physics.settings import DEFAULT_UNIT, Physics


def test_contacts_are_warm_started_only_when_asked(scene):
    scene.set_physics("dynamic")
    assert not scene.bodies.physics.dynamics.warm_started  # off by default: tasks as measured
    scene.set_physics("dynamic", {"warmStart": 0.85})
    assert scene.bodies.physics.dynamics.warm_started
    assert scene.physics.wire()["warmStart"] == 0.85


@pytest.mark.parametrize("iterations", [24, 25])
def test_a_motor_holds_its_arm_out_whatever_the_solvers_iterations(scene, iterations):
    # a robot's base without a part is as hard to turn as its load about it: its load was
    # weighed at its parts' frames, so an arm whose frame is at its motor weighed nothing,
    # the base turned under it as easily as a small ball, and the arm fell at every odd
    # count of iterations (2.6 rad at 25, 35, 49 or 61) while it held at every even one
    robot = Robot(scene, "r")
    motor = MotorZ(scene, "m")
    arm = EdgedFinger(scene, "f", 2.0)
    robot.attach_chain(motor, arm)
    robot.set_position((0, 3, 0))
    motor.set_angle(-math.pi / 2)  # sideways: gravity turns it down
    motor.set_max_torque(1e5)
    scene.set_physics("dynamic", {"unit": 1.0, "solverIterations": iterations})
    for _ in range(90):
        scene.tick(1 / 60)
    assert motor.angle == pytest.approx(-math.pi / 2, abs=0.01)


def test_the_default_torque_holds_a_hand_level():
    # an edged finger at the default unit and density (segments of about 0.08 cubic scene
    # units, 16 g, their centres 0.5, 1.5 and 2.5 scene units out) held level under
    # 9.81 m/s², with room to grip
    segment = Physics().density * 0.08 * DEFAULT_UNIT ** 3
    assert DEFAULT_MAX_TORQUE > 2 * segment * 9.81 * DEFAULT_UNIT * (0.5 + 1.5 + 2.5)


def test_a_tick_takes_no_more_steps_than_its_budget_and_costly_steps_get_fewer_iterations(scene):
    # 500 iterations of 20 substeps under gravity 1000 took one tick 10.7 s: past the
    # budget a tick leaves its other steps out, and a step that costs more than the whole
    # budget gets fewer iterations, given back once steps are cheap again
    scene.set_physics("dynamic", {"gravity": 1000, "substeps": 20, "solverIterations": 500})
    Box(scene, "box").set_position((0, 3, 0))
    scene.tick(1 / 60)
    world = scene.bodies.physics.dynamics
    cost = [3 * dynamics.STEP_BUDGET]  # CPU-seconds a step costs, as the clock tells it
    readings = iter(range(10**6))
    world.clock = lambda: next(readings) * cost[0]  # a step: from one reading to the next
    before = scene.time
    scene.tick(1 / 60)
    assert world.held_back == 19 and scene.time - before == pytest.approx(1 / 1200)
    assert world.stepping == pytest.approx(3 * dynamics.STEP_BUDGET)  # the one step's cost
    assert world.iterations == int(500 / 3 * 0.8)
    cost[0] = dynamics.STEP_BUDGET / 10
    for _ in range(4):
        scene.tick(1 / 60)
    assert world.iterations == 500 and world.held_back < 19


def test_a_scene_a_script_steps_takes_every_step_with_every_iteration_whatever_they_cost(scene):
    # the finding: the same seeded grasp ended differently on a busy machine, as the
    # budget of CPU time left steps out of a stepped run
    scene.set_physics("dynamic", {"substeps": 20, "solverIterations": 500})
    Box(scene, "box").set_position((0, 3, 0))
    scene.tick(1 / 60)
    world = scene.bodies.physics.dynamics
    readings = iter(range(10**6))
    world.clock = lambda: next(readings) * 3 * dynamics.STEP_BUDGET  # every step costly
    scene.tick(1 / 60)
    assert world.held_back == 19 and world.iterations < 500  # running: the budget holds
    scene.pause("script")
    scene.step(1)
    scene.tick(1 / 60)  # the tick the script asked for
    assert world.held_back == 0 and world.iterations == 500
    assert world.stepping == 0.0  # (untimed)


def test_a_crowd_comes_to_rest_and_wakes_when_one_is_put_elsewhere_or_one_goes(scene):
    # 500 balls heaped never came to rest (their jitter kept every one moving, and every
    # tick paid for them all); past SLEEP_CROWD free bodies, resting ones sleep
    scene.set_physics("dynamic")
    scene.clock.pause("test")  # every step taken: the heap's ticks pass the CPU budget
    # of a slow machine, whose left-out steps and fewer iterations keep it stirring longer
    count = dynamics.SLEEP_CROWD + 50
    with scene.journal.transaction():
        balls = [Ball(scene, f"b{i}", 0.2) for i in range(count)]
        for ball in balls:
            ball.set_position((0, 2, 0))
    ticks = 0
    scene.tick(1 / 60)
    while scene.moving:
        scene.tick(1 / 60)
        ticks += 1
        assert ticks < 3000, "the heap never came to rest"
    lowest = min(balls, key=lambda b: b.position[1])
    highest = max(balls, key=lambda b: b.position[1])
    highest.set_position((30, 10, 0))  # put elsewhere: it falls, asleep or not
    for _ in range(30):
        scene.tick(1 / 60)
    assert highest.position[1] < 9
    before = {ball.id: ball.position for ball in balls if ball is not lowest and ball is not highest}
    scene.delete(lowest)  # what it held up wakes
    for _ in range(30):
        scene.tick(1 / 60)
    assert any(scene.nodes[i].position != p for i, p in before.items())


def test_a_world_at_rest_is_not_stepped_until_something_changes(scene):
    # a settled heap of 2 000 sleeping balls still cost Bullet 2.5 ms a step (30 ticks a
    # second at best); nothing moved, so nothing would: its steps are counted, not taken
    scene.set_physics("dynamic")
    count = dynamics.SLEEP_CROWD + 20
    with scene.journal.transaction():
        balls = [Ball(scene, f"b{i}", 0.2) for i in range(count)]
        for k, ball in enumerate(balls):
            ball.set_position((k % 17 * 0.5, 0.2, k // 17 * 0.5))
    ticks = 0
    while scene.moving or ticks < 5:
        scene.tick(1 / 60)
        ticks += 1
        assert ticks < 3000, "the balls never came to rest"
    world = scene.bodies.physics.dynamics
    scene.tick(1 / 60)  # (the tick that finds nothing moved)
    steps, before, contacts = world.steps, scene.time, scene.bodies.contacts.wire()
    for _ in range(10):
        scene.tick(1 / 60)
    assert world.steps == steps and scene.time - before == pytest.approx(10 / 60)
    assert scene.bodies.contacts.wire() == contacts and len(contacts) >= count  # still on the ground
    balls[0].set_position((0, 3, 0))  # put somewhere: the world steps again, and it falls
    for _ in range(30):
        scene.tick(1 / 60)
    assert world.steps > steps and balls[0].position[1] < 2.5


@pytest.mark.parametrize("unit", [DEFAULT_UNIT, 1.0])
def test_a_ball_falls_at_g_in_metres_whatever_the_unit(scene, unit):
    ball = Ball(scene, "b", 0.25)
    ball.set_position((0, 50 / unit, 0))  # 50 m up
    scene.set_physics("dynamic", {"unit": unit})
    for _ in range(12):  # (Bullet's drag, which grows with speed², is small this soon)
        scene.tick(1 / 60)
    fallen = (50 / unit - ball.position[1]) * unit  # metres
    assert fallen == pytest.approx(9.81 * scene.time ** 2 / 2, rel=0.05)


def test_a_resting_box_presses_with_its_weight_in_newtons(scene):
    pad = Box(scene, "pad", 4, 0.2, 4)
    pad.set_static(True)
    pad.set_position((0, 0.1, 0))
    sensor = Sensor(scene, "s")
    sensor.attach_to_slot(pad)
    load = Box(scene, "load", 1, 1, 1)  # a cube of 5.4 cm at the default unit
    load.set_position((0, 0.7, 0))
    scene.set_physics("dynamic")
    for _ in range(90):
        scene.tick(1 / 60)
    mass = load.get_mass()
    assert mass == pytest.approx(scene.physics.density * DEFAULT_UNIT ** 3)  # kg
    assert sensor.sense_force() == pytest.approx(mass * 9.81, rel=0.05)  # N, about 2 N
