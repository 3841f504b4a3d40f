"""Sensor readings along +Y: distances, the touch ramp, what rays see and what they do not."""

import math

import pytest

from server.core.model.hands import RoundHand
from server.core.model.gltf_parts import RoundFinger
from server.core.model.motor import MotorX
from server.core.model.parts import Ball, Box, EdgedFinger
from server.core.model.sensor import Sensor

DOWN = (math.pi, 0, 0)  # turns the sensing direction +Y to -Y


def sensor_at(scene, height, name="s", rotation=DOWN):
    sensor = Sensor(scene, name)
    sensor.set_position((0, height, 0))
    sensor.set_rotation(*rotation)
    return sensor


@pytest.mark.parametrize("height", [0.05, 0.3, 1.0, 2.5, 40.0])
def test_sensor_pointing_down_reads_its_height(scene, height):
    assert sensor_at(scene, height).sense_distance() == pytest.approx(height, abs=1e-12)


def test_sensor_pointing_up_at_nothing_reads_infinity(scene):
    assert sensor_at(scene, 1.0, rotation=(0, 0, 0)).sense_distance() == math.inf


def test_hits_nearer_than_the_pad_are_ignored(scene):
    low = sensor_at(scene, 0.03)
    assert low.sense_distance() == math.inf  # the ground is within 0.05, nothing beyond
    Box(scene, "shelf", 1, 0.1, 1).set_position((0, 0.5, 0))
    low.set_rotation(0, 0, 0)
    assert low.sense_distance() == pytest.approx(0.42, abs=1e-12)  # underside at 0.45


@pytest.mark.parametrize("height, touch", [(0.0, 1.0), (0.01, 0.8), (0.025, 0.5),
                                           (0.05, 0.0), (0.2, 0.0)])
def test_touch_ramps_from_zero_to_one_over_the_last_five_centimetres(scene, height, touch):
    assert sensor_at(scene, height).sense_touch() == pytest.approx(touch, abs=1e-12)


def test_motors_and_sensors_are_transparent_parts_are_not(scene):
    sensor = sensor_at(scene, 2.0)
    MotorX(scene, "motor", 0, 1, 0, 1, 1).set_position((0, 1, 0))
    sensor_at(scene, 1.5, "other")
    assert sensor.sense_distance() == pytest.approx(2.0, abs=1e-12)
    Ball(scene, "ball", 0.25).set_position((0, 1, 0))
    assert sensor.sense_distance() == pytest.approx(0.75, abs=1e-12)


def test_direction_follows_the_slot_the_sensor_is_attached_to(scene):
    finger = EdgedFinger(scene, "f")
    finger.set_position((0, 1, 0))
    finger.set_rotation(0, 0, math.pi / 2)  # the finger, and its slot, point along -X
    sensor = Sensor(scene, "s").attach_to_slot(finger)
    Box(scene, "wall", 0.2, 3, 3).set_position((-3, 1, 0))
    assert sensor.sense_position() == pytest.approx((-1, 1, 0))
    assert sensor.sense_distance() == pytest.approx(1.9, abs=1e-12)


def _underside(scene, kind):
    """A body whose underside is flat where a sensor below (x = z = 0) looks up, and its height."""
    if kind == "box":
        Box(scene, "b", 1, 0.1, 1).set_position((0, 1, 0))
        return 0.95
    if kind == "ball":
        Ball(scene, "b", 0.5).set_position((0, 1.5, 0))
        return 1.0
    if kind == "edged":  # the flat end of the profile, EDGE_EPSILON above the part's origin
        EdgedFinger(scene, "b").set_position((0.05, 1, 0))
        return 1.003
    finger = RoundFinger(scene, "b", "round-finger-8.glb", 0.8)  # its flat connector disc
    finger.set_position((0, 1, 0))
    return 1 + 0.4 + float(finger.mesh.vertices[:, 1].min())


GAPS = [0.0, 0.001, 0.01, 0.03, 0.049, 0.0499, 0.04999999, 0.05, 0.05000001, 0.0501, 0.051, 0.1, 0.5]


@pytest.mark.parametrize("kind", ["box", "ball", "edged", "round"])
def test_a_sweep_of_gaps_reads_as_in_1_0(scene, kind):
    face = _underside(scene, kind)
    Box(scene, "shelf", 20, 0.1, 20).set_position((0, 4.05, 0))  # what lies beyond: at 4
    sensor = Sensor(scene, "s")
    for gap in GAPS:
        sensor.set_position((0, face - gap, 0))
        touch, distance = sensor.sense_touch(), sensor.sense_distance()
        assert touch == pytest.approx(max(0.0, 1 - gap / 0.05), abs=1e-9), gap
        if gap >= 0.05:
            assert distance == pytest.approx(gap, abs=1e-9), gap
        else:  # nearer than the pad: ignored, the next body beyond is read
            assert distance == pytest.approx(4 - (face - gap), abs=1e-9), gap


@pytest.mark.parametrize("kind", ["box", "ball", "edged", "round"])
def test_a_sensor_inside_a_body_reads_the_next_body_beyond(scene, kind):
    face = _underside(scene, kind)
    Box(scene, "shelf", 20, 0.1, 20).set_position((0, 4.05, 0))
    sensor = Sensor(scene, "s")
    sensor.set_position((0, face + 0.02, 0))
    assert sensor.sense_distance() == pytest.approx(4 - face - 0.02, abs=1e-9)
    assert sensor.sense_touch() == 0.0


def test_a_sensor_on_a_round_fingertip_reads_exact_distances(scene):
    hand = RoundHand(scene, "h")
    hand.flex_fingers(0.3)
    tip = [p for p in hand.get_parts() if p.type_name == "RoundFinger"][5]  # index finger tip
    assert tip.mesh.url.endswith("round-tip.glb")
    sensor = Sensor(scene, "s").attach_to_slot(tip)
    Box(scene, "ceiling", 30, 0.2, 30).set_position((0, 8, 0))  # underside at 7.9
    (px, py, pz), (x, y, z, w) = sensor.world_pose()
    rising = 1 - 2 * (x * x + z * z)  # the sensor's +Y, upwards part
    assert 0.5 < rising < 1  # tilted by the flexed finger
    assert sensor.sense_distance() == pytest.approx((7.9 - py) / rising, abs=1e-9)
    assert sensor.sense_touch() == 0.0  # the tip's own mesh is seen from inside: not at all
