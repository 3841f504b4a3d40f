"""Every part type in one scene, in a row, for looking at the viewer's drawing of each.

    .venv/bin/python clients/python/examples/all_parts.py [ws://127.0.0.1:8000] [scene]

Then open /view?scene=<scene>&show-slots or &debug-physics.
"""

from __future__ import annotations

import math
import sys

import virtual_prosthetics as vp


def build() -> dict[str, vp.Node]:
    """One of each part, and an edged hand; returns them by name."""
    parts: dict[str, vp.Node] = {
        "ball": vp.Ball(0.3, "tomato"), "box": vp.Box(0.5, 0.3, 0.4, "steelblue"),
        "finger": vp.EdgedFinger(0.8), "tip": vp.EdgedTip(0.6), "palm": vp.EdgedPalm(True),
        "motor_x": vp.MotorX(), "motor_y": vp.MotorY(), "motor_z": vp.MotorZ(),
        "sensor": vp.Sensor(True, True),
    }
    heights = {"ball": 0.3, "box": 0.15, "palm": 0.0, "finger": 0.0, "tip": 0.0}
    for k, (name, part) in enumerate(parts.items()):
        part.set_position(-4 + 1.0 * k, heights.get(name, 0.4), 1.5)
    parts["sensor"].set_rotation(0, 0, math.pi / 2)  # its laser points along -X, at the motors
    hand = vp.EdgedHand(False)
    hand.set_position(0, 0, -1.5)
    hand.flex_fingers(0.4)
    hand.add_gui("Edged hand")
    parts["hand"] = hand
    vp.set_camera_position(0, 4, 12)
    vp.set_camera_target(0, 0.8, 0)
    return parts


if __name__ == "__main__":
    vp.connect(*sys.argv[1:2], **({"scene": sys.argv[2]} if len(sys.argv) > 2 else {}))
    build()
    vp.run()
