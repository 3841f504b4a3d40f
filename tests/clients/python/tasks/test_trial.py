"""A trial against the real server: what keeping a hand's targets and its wrist costs it."""

import pytest

from virtual_prosthetics.tasks import grasp
from virtual_prosthetics.tasks.controller import prepare
from virtual_prosthetics.tasks.hands import hand_source
from virtual_prosthetics.tasks.trial import TaskHand, drive, lay_out


def test_targets_kept_cost_the_server_no_request_and_the_hand_holds_them(server, scene, scene_name):
    # found: a grasp's steps sent the motors' targets every tick, the same for four fifths
    # of its ticks: each a request the server decoded, checked and applied to no effect
    scene.set_physics("dynamic")
    ball = grasp.PATTERNS[0]

    def requests() -> int:
        return server.figures(scene_name)["requests"]
    with scene.paused():  # stepped: the same motion however loaded the machine is
        [trial] = lay_out(scene, TaskHand(hand_source("edged", scene)), ball.item, [(1.0, 1.0)],
                          ball.item.light, ball.grip)
        prepare(trial.hand, ball.grip)  # the task's torques: the digits close in the air
        half = trial.grip.angles({i: 0.5 for i in range(len(trial.grip.digits))})
        scene.sync()
        before = requests()
        for _ in range(3):
            trial.set_motors(*half)
            scene.sync()
        assert requests() - before == 1  # the first; the same again: nothing
        drive(scene, 0.5, lambda t: None)  # the motors drive to the targets sent once
        angles = trial.hand.get_angles()
        closing = [i for i, target in enumerate(half) if target is not None and abs(target) > 0.1]
        assert closing and all(abs(angles[i] - half[i]) < abs(half[i]) / 2 for i in closing), \
            (angles, half)
        before = requests()
        trial.set_motors(*trial.grip.angles({i: 0.0 for i in range(len(trial.grip.digits))}))
        scene.sync()
        assert requests() - before == 1  # a change is sent


def test_a_wrist_kept_costs_the_server_no_request_and_the_hand_stays_held(server, scene, scene_name):
    # the wrist held still (three quarters of a grasp) was sent every tick all the same
    scene.set_physics("dynamic")
    ball = grasp.PATTERNS[0]

    def requests() -> int:
        return server.figures(scene_name)["requests"]
    with scene.paused():
        [trial] = lay_out(scene, TaskHand(hand_source("edged", scene)), ball.item, [(1.0, 1.0)],
                          ball.item.light, ball.grip)
        x, y, z = trial.home
        scene.sync()
        before = requests()
        for _ in range(3):
            trial.set_wrist(x, y + 1, z)
            scene.sync()
        assert requests() - before == 1  # the first; the same again: nothing
        drive(scene, 0.5, lambda t: None)
        assert trial.hand_position()[1] == pytest.approx(y + 1, abs=0.01)  # held there
        before = requests()
        trial.set_wrist(x, y, z)
        scene.sync()
        assert requests() - before == 1  # a change is sent
