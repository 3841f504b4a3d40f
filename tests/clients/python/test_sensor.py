"""The Python client's sensors and contact callbacks against a real server."""

from __future__ import annotations

import math

import pytest

import virtual_prosthetics as vp
from tests.conftest import eventually

DOWN = (math.pi, 0, 0)


def test_exact_readings_reflect_earlier_writes(scene):
    sensor = vp.Sensor()
    sensor.set_rotation(*DOWN)
    for height in (0.4, 1.25, 3.0):
        sensor.set_position(0, height, 0)
        assert sensor.sense_distance() == pytest.approx(height, abs=1e-4)
        assert sensor.sense_position() == pytest.approx([0, height, 0])
    sensor.set_rotation(0, 0, 0)
    assert sensor.sense_distance() == math.inf
    sensor.set_position(0, 0.01, 0)
    sensor.set_rotation(*DOWN)
    assert sensor.sense_touch() == pytest.approx(0.8, abs=1e-4)


def test_watched_readings_come_with_the_frames(scene):
    sensor = vp.Sensor()  # no laser: not watched (no readings in frames) until watch()
    sensor.set_position(0, 2, 0)
    sensor.set_rotation(*DOWN)
    sensor.watch()
    eventually(lambda: sensor.id in scene.mirror.readings)  # until then: exact reads
    assert sensor.sense_distance() == pytest.approx(2.0, abs=1e-4)
    sensor.set_position(0, 1, 0)
    assert sensor.sense_distance(exact=True) == pytest.approx(1.0, abs=1e-4)
    eventually(lambda: sensor.sense_position() == pytest.approx([0, 1, 0]))
    assert sensor.sense_distance() == pytest.approx(1.0, abs=1e-4)
    assert scene.mirror.readings[sensor.id]["distance"] == pytest.approx(1.0, abs=1e-4)


def test_sense_objects_gives_own_objects_other_clients_ids_and_ground(server, scene,
                                                                     scene_name):
    finger = vp.EdgedFinger()
    finger.set_position(0, -0.2, 0)
    sensor = vp.Sensor().attach_to_slot(finger)
    box = vp.Box(1, 0.1, 0.1)
    box.set_position(0, 0.5, 0)
    with vp.Session(server.ws, scene=scene_name) as other:
        theirs = vp.Ball(0.2, scene=other)
        theirs.set_position(0, 0.3, 0)
        other.sync()
        assert sensor.sense_objects() == sorted([box, theirs.id, "ground"],
                                                key=lambda o: getattr(o, "id", o))
        assert sensor.sense_collision() and sensor.sense_object(box)
        assert sensor.sense_object("ground") and sensor.sense_object(theirs.id)
    with pytest.raises(TypeError):
        sensor.sense_object(42)


class Recorder(vp.Box):
    """A box that notes its contacts, as the manual's MyPart example does."""

    def __init__(self, *args, **kwargs):
        self.log = []
        super().__init__(*args, **kwargs)

    def begin_contact(self, other):
        self.log.append(("begin", other))

    def end_contact(self, other):
        self.log.append(("end", other))


def test_contact_callbacks_run_once_per_change_in_order(scene):
    finger = vp.EdgedFinger()
    finger.set_position(0, 1, 0)
    box = Recorder(1, 0.1, 0.1)  # made at the origin, half in the ground
    vp.set_animation(lambda: None)

    def logged(count):  # (a loaded machine may take longer than a run of 0.2 s to tell)
        vp.run(0.2)
        scene.sync()
        eventually(lambda: (scene.dispatch_contacts(), len(box.log) >= count)[1])
    logged(1)
    assert box.log == [("begin", "ground")]
    box.set_position(0, 1.5, 0)  # across the finger
    logged(3)
    assert box.log[1:] == [("begin", finger), ("end", "ground")]
    box.set_position(0, 0.02, 0)  # onto the ground
    logged(5)
    assert box.log[3:] == [("begin", "ground"), ("end", finger)]
    box.set_position(0, 3, 0)
    scene.sync()
    eventually(lambda: (scene.dispatch_contacts(), len(box.log) == 6)[1])
    assert box.log[5] == ("end", "ground")
    vp.run(0.2)
    assert len(box.log) == 6  # nothing more changed


def test_run_without_an_animation_still_delivers_callbacks(scene):
    box = Recorder(0.5, 0.5, 0.5)
    box.set_position(0, 0, 0)
    vp.run(0.2)
    assert box.log == [("begin", "ground")]
    assert scene.mirror.contacts == {(box.id, "ground")}  # the mirror keeps the pairs too


def test_reading_a_deleted_sensor_raises_a_clear_error(scene):
    sensor = vp.Sensor().watch()
    sensor.delete()
    with pytest.raises(vp.ServerError) as caught:
        sensor.sense_distance()
    assert caught.value.code == "unknown_object" and "was deleted" in caught.value.message
    with pytest.raises(TypeError, match="needs a part or 'ground'"):
        vp.Sensor().sense_object(vp.Robot())


def test_only_parts_with_callbacks_keep_contact_changes(scene):
    plain, listening = vp.Box(0.5, 0.5, 0.5), Recorder(0.5, 0.5, 0.5)
    plain.set_position(-2, 0, 0)
    listening.set_position(2, 0, 0)
    scene.sync()
    eventually(lambda: (plain.id, "ground") in scene.mirror.contacts
               and (listening.id, "ground") in scene.mirror.contacts)
    # the change is queued, or already handed to the callback (the mirror's thread may
    # move it between the two looks, so it can be seen in both); nothing of plain's
    kept = {event[1] for event in scene.mirror.events} | {listening.id for _ in listening.log}
    assert kept == {listening.id}
    assert not plain.hears_contacts and listening.hears_contacts
