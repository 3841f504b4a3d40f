"""Grippers designed by the tests, which no table of the tasks knows (``--hand
tests.clients.python.tasks.gripper:three_digits`` builds one from the command line)."""

from __future__ import annotations

import math

import virtual_prosthetics as vp

ROOTS = {"thumb": (0.0, -0.7), "left": (-0.5, 0.7), "right": (0.5, 0.7)}  # (x, z) on the palm


def three_digits(session: vp.Session) -> vp.Robot:
    """A box palm and three digits pointing down from its underside, each a MotorX, an
    EdgedFinger, a MotorX and an EdgedTip: one on the -z side opposing two on the +z side."""
    robot = vp.Robot(scene=session)
    palm = vp.Box(2.0, 0.4, 2.0, "slategray", scene=session)
    robot.attach_chain(palm)
    for name, (x, z) in ROOTS.items():
        slot = palm.add_slot(x, -0.2, z)
        slot.set_rotation(math.pi, 0, 0)  # a finger grows along its +y: this points it down
        base, middle = (vp.MotorX(-1.3, 1.3, 0, scene=session).set_name(f"{name} base"),
                        vp.MotorX(-1.3, 1.3, 0, scene=session).set_name(f"{name} middle"))
        base.attach_to_slot(palm, slot)
        robot.add_chain(base, vp.EdgedFinger(0.7, scene=session), middle, vp.EdgedTip(scene=session))
    return robot
