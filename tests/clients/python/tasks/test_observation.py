"""What a controller observes, against the real server: angles, speeds and torques of
the hand's motors, each digit's force on the object (not the table), the object's pose
in the hand."""

import math

from virtual_prosthetics.tasks import grasp
from virtual_prosthetics.tasks.controller import PHASES, baseline
from virtual_prosthetics.tasks.hands import hand_source
from virtual_prosthetics.tasks.trial import TaskHand


def test_a_controller_sees_its_motors_the_forces_of_each_digit_and_the_object_in_the_hand(scene):
    seen_all, table_under = [], []

    def watching(grip):
        scripted = baseline(grip)

        def control(seen):
            seen_all.append(seen)
            if seen.t >= PHASES.closing:
                seen.speeds, seen.torques  # asked of the server while it is there
            seen.angles, seen.digit_forces, seen.object_position, seen.object_quaternion
            if seen.t < PHASES.hover:  # the hand still high above the ball
                table_under.append((seen.digit_forces, seen._trial.object_contacts()))
            return scripted(seen)
        return control

    result = grasp.grasp(scene, TaskHand(hand_source("edged", scene)), 1, seed=3,
                         patterns=["spherical"], controller=watching)
    assert result["results"][0]["successes"] == 1
    first = [s for s in seen_all if s.t == 0.0][0]  # the light ball's trial
    trial_steps = seen_all[:seen_all.index([s for s in seen_all if s.t == 0.0][1])]
    grip = first.grip
    assert len(first.angles) == grip.motors
    # before the hand came down nothing pressed the ball but the table (its weight, which
    # the ball's sensor reads): every digit 0
    resting = table_under[-1]  # the last step before the hand comes down
    assert resting[0] == [0.0] * len(grip.digits)
    assert [c["normal"] > 0 for c in resting[1]] == [True]
    held = [s for s in trial_steps if s.t >= PHASES.holding]
    # in the hold two digits or more press it, each told apart
    pressing = [sum(f > 0 for f in s.digit_forces) for s in held]
    assert min(pressing) >= 2
    # the closing motors turned while closing and strain against the ball in the hold
    closing = [m.index for d in grip.digits for m in d.motors]
    moving = [s for s in trial_steps if PHASES.closing <= s.t < PHASES.lifting]
    assert max(abs(s.speeds[i]) for s in moving for i in closing) > 1.0
    assert len(held[-1].speeds) == grip.motors
    assert max(abs(held[-1].torques[i]) for i in closing) > 0.01
    # the ball stays put in the hand's frame, about a ball's radius and more from its origin
    start, end = held[0].object_position, held[-1].object_position
    assert math.dist(start, end) < 0.005 and 0.02 < math.dist(end, (0, 0, 0)) < 0.2
    # and turns with it: its turn in the hand's frame is the same at the hold's two ends
    # (the hand turned palm down: the ball's turn in the world is not)
    turn = abs(sum(a * b for a, b in zip(held[0].object_quaternion, held[-1].object_quaternion)))
    assert turn > 0.99 and abs(held[-1].object_quaternion[3]) < 0.99
    slips = result["results"][0]
    assert slips["slipFromContact"] >= slips["slip"]  # closing and lifting moved it too
