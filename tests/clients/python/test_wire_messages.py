"""What the Python client sends is what its typed definitions (and so the schema) say."""

from __future__ import annotations

from typing import get_type_hints

import virtual_prosthetics as vp
from virtual_prosthetics.wire_messages import CLIENT_MESSAGES


def test_every_message_a_script_sends_has_its_definitions_keys(scene):
    sent: list[dict] = []
    core = scene.connection.core
    request = core.request
    core.request = lambda message, wait=False: (sent.append(dict(message)), request(message, wait))[1]
    robot = vp.Robot()
    motor = vp.MotorZ(-1, 1)
    robot.attach_chain(motor, vp.EdgedFinger())
    robot.set_angles(0.5)
    vp.set_camera_position(1, 2, 3)
    vp.Box().delete()
    scene.sync()
    assert {"create", "call", "delete"} <= {message["op"] for message in sent}
    for message in sent:
        definition = CLIENT_MESSAGES[message["op"]]
        keys = set(message) - {"id"}  # the protocol core numbers each request
        assert keys <= set(get_type_hints(definition)), message
        assert definition.__required_keys__ <= set(message), message
