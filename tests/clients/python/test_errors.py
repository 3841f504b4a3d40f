"""What goes wrong reaches a script as the client's errors, with the server's code and details."""

from __future__ import annotations

import pytest

import virtual_prosthetics as vp


def test_errors_are_raised_as_server_errors(scene):
    robot = vp.Robot()
    robot.set_angles("fast")  # returns at once; the error comes with the next read
    with pytest.raises(vp.ServerError) as caught:
        robot.get_angles()
    assert caught.value.code == "wrong_type" and "setAngles" in caught.value.message
    finger = vp.EdgedFinger()
    finger.attach_to_slot(finger)
    with pytest.raises(vp.ServerError) as caught:
        scene.sync()
    assert caught.value.code == "cycle"
    assert robot.get_angles() == []  # the connection carries on
