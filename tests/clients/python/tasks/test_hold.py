"""``hold`` against the real server: balls carried round a path, drops counted."""

from virtual_prosthetics.tasks import hold
from virtual_prosthetics.tasks.hands import hand_source
from virtual_prosthetics.tasks.observation import Angles
from virtual_prosthetics.tasks.trial import TaskHand


def test_the_baseline_carries_each_ball_round_the_path_without_a_drop(scene):
    result = hold.hold(scene, TaskHand(hand_source("edged", scene)), 2, seed=1)
    assert result["task"] == "hold" and result["trials"] == 2
    assert result["drops"] == 0  # the baseline grasp holds through the path


def test_a_hand_that_lets_go_drops_every_ball(scene):
    def lets_go(grip):
        baseline = hold.baseline(grip)

        def control(seen):
            if seen.t > hold.PHASES.lifting + 0.5:
                return Angles(seen.grip.angles({i: 0.0 for i in range(len(seen.grip.digits))}))
            return baseline(seen)
        return control

    assert hold.hold(scene, TaskHand(hand_source("edged", scene)), 1, seed=1, controller=lets_go)["drops"] == 1
