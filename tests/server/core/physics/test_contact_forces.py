"""Forces per contact: who presses on a part, and how hard, in newtons."""

import math

import pytest

from server.core.model.parts import Box
from server.core.model.sensor import Sensor
from server.core.physics.contact_forces import ContactForce, contacts_by_part, forces_by_part

G = 9.81


def _stack(scene):
    """A cube on a static table and a lighter block on the cube, settled; a sensor on the cube."""
    table = Box(scene, "table", 4, 0.2, 4)
    table.set_static(True)
    table.set_position((0, 0.1, 0))
    cube = Box(scene, "cube", 1, 1, 1)
    cube.set_position((0, 0.7, 0))
    sensor = Sensor(scene, "s")
    sensor.attach_to_slot(cube)
    block = Box(scene, "block", 0.5, 0.5, 0.5)
    block.set_position((0, 1.45, 0))
    scene.set_physics("dynamic")
    cube.set_mass(0.2)
    block.set_mass(0.05)
    for _ in range(120):
        scene.tick(1 / 60)
    return sensor, table, block


def test_a_part_tells_the_force_of_each_body_pressing_on_it(scene):
    sensor, table, block = _stack(scene)
    # the finding: a fingertip on the table read ~3 N "on the object" before touching it
    assert sensor.sense_force(block) == pytest.approx(0.05 * G, rel=0.05)
    assert sensor.sense_force(table) == pytest.approx(0.25 * G, rel=0.05)  # cube and block
    assert sensor.sense_force() == pytest.approx(0.30 * G, rel=0.05)      # all of them
    assert sensor.sense_force("ground") == 0.0
    contacts = sensor.sense_contacts()
    assert [c["other"] for c in contacts] == ["table", "block"]  # the largest first
    assert all(c["friction"] < 0.05 * c["normal"] for c in contacts)  # at rest: no sliding
    assert sensor.reading().touch == 1.0  # pressed on: touched, whatever the pad's ray sees


def test_friction_holds_a_part_on_a_slope(scene):
    slope = 0.2  # radians: less than the friction angle, the cube stays
    table = Box(scene, "table", 6, 0.2, 6)
    table.set_static(True)
    table.set_rotation(0, 0, slope)
    table.set_position((0, 1, 0))  # its ends clear the ground
    cube = Box(scene, "cube", 1, 1, 1)
    cube.set_rotation(0, 0, slope)
    cube.set_position((-0.6 * math.sin(slope), 1 + 0.6 * math.cos(slope), 0))
    sensor = Sensor(scene, "s")
    sensor.attach_to_slot(cube)
    scene.set_physics("dynamic")
    cube.set_mass(0.2)
    for _ in range(90):
        scene.tick(1 / 60)
    [on_table] = sensor.sense_contacts()
    assert on_table["other"] == "table"
    assert on_table["normal"] == pytest.approx(0.2 * G * math.cos(slope), rel=0.05)
    assert on_table["friction"] == pytest.approx(0.2 * G * math.sin(slope), rel=0.05)


def test_kinematic_mode_presses_nothing(scene):
    sensor, table, block = _stack(scene)
    scene.set_physics("kinematic")
    assert sensor.sense_contacts() == [] and sensor.sense_force(block) == 0.0
    assert "table" in sensor.sense_objects()  # touching is still told


def _point(a, b, normal, friction=(0.0, 0.0)):
    return (0, a, b, -1, -1, None, None, (0, 1, 0), 0.0, normal,
            friction[0], (1, 0, 0), friction[1], (0, 0, 1))


def test_frictions_on_one_body_add_as_vectors_and_normals_as_magnitudes():
    keys_of = {1: ["p"], 2: ["q"], 3: [None]}
    points = [_point(1, 2, 2.0, (1.0, 0.0)), _point(1, 2, 2.0, (-1.0, 0.0)),  # cancel
              _point(2, 1, 1.0, (0.0, 2.0)), _point(1, 3, 5.0), _point(1, 9, 5.0)]
    # body 9 left the world since the step: passed over; body 3's link has no part
    found = contacts_by_part(points, keys_of, {"p"}, newtons=2.0)
    assert found == {"p": (ContactForce("q", 10.0, 4.0),)}
    assert forces_by_part(points[:4], keys_of) == {"p": 10.0, "q": 5.0}
