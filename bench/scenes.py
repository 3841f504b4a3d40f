"""The benchmark scenes, defined once as protocol operations for every measure.

The same operations build a scene in-process (through a :class:`Session`) and on a
running server (over a WebSocket), and the same step function animates both, so the
figures measured in-process and from outside are of one scene.

- hands-N: N EdgedHands (alternately left and right) on a grid 4 units apart, each
  flexing and spreading its fingers with a phase of its own;
- arms-11: eleven three-segment arms 0.8 apart, swinging into their neighbours.
"""

from __future__ import annotations

import math
from typing import Any

GRID = 4.0
ARMS = 11
ARM_GAP = 0.8
ARM_SEGMENTS = 3

Op = dict[str, Any]


def hands(client: str, count: int) -> list[Op]:
    """Operations that make hands-``count`` for ``client`` (ids ``{client}.h{i}``)."""
    columns = max(1, math.ceil(math.sqrt(count)))
    ops: list[Op] = []
    for i in range(count):
        hand = f"{client}.h{i}"
        ops.append({"op": "create", "object": hand, "type": "EdgedHand", "args": [i % 2 == 0]})
        ops.append({"op": "call", "object": hand, "method": "setPosition",
                    "args": [(i % columns) * GRID, 0, (i // columns) * GRID]})
    return ops


def hand_step(client: str, count: int, step: int) -> list[Op]:
    """One animation step of hands-``count``: every hand flexes and spreads its fingers."""
    ops: list[Op] = []
    for i, (flex, spread) in enumerate(hand_angles(count, step)):
        hand = f"{client}.h{i}"
        ops.append({"op": "call", "object": hand, "method": "flexFingers", "args": [flex]})
        ops.append({"op": "call", "object": hand, "method": "spreadFingers", "args": [spread]})
    return ops


def hand_angles(count: int, step: int) -> list[tuple[float, float]]:
    """Per hand, its flex and spread angle at ``step`` (a phase per hand)."""
    return [(0.8 * (0.5 + 0.5 * math.sin(step / 20 + i)), 0.3 * math.sin(step / 15 + i))
            for i in range(count)]


def arms(client: str) -> list[Op]:
    """Operations that make arms-11 (ids ``{client}.a{k}``, motors ``{client}.a{k}m{j}``)."""
    ops: list[Op] = []
    for k in range(ARMS):
        arm = f"{client}.a{k}"
        chain = []
        ops.append({"op": "create", "object": arm, "type": "Robot"})
        for j in range(ARM_SEGMENTS):
            motor, segment = f"{arm}m{j}", f"{arm}s{j}"
            ops.append({"op": "create", "object": motor, "type": "MotorZ"})
            ops.append({"op": "create", "object": segment, "type": "EdgedFinger"})
            chain += [motor, segment]
        ops.append({"op": "call", "object": arm, "method": "attachChain",
                    "args": [{"ref": name} for name in chain]})
        ops.append({"op": "call", "object": arm, "method": "setPosition",
                    "args": [k * ARM_GAP, 0, 0]})
    return ops


def arm_step(client: str, step: int) -> list[Op]:
    """One animation step of arms-11: every joint swings, each arm in its own phase."""
    return [{"op": "call", "object": f"{client}.a{k}", "method": "setAngles",
             "args": [0.7 * math.sin(step / 15 + k + j) for j in range(ARM_SEGMENTS)]}
            for k in range(ARMS)]


def dynamic(client: str, count: int, objects: int) -> list[Op]:
    """hands-``count`` in dynamic mode, held a hand's length up, with ``objects`` free
    balls and boxes dropped among them (ids ``{client}.o{k}``); PyBullet's defaults."""
    ops = hands(client, count)
    columns = max(1, math.ceil(math.sqrt(count)))
    for i in range(count):
        hand = f"{client}.h{i}"
        ops.append({"op": "call", "object": hand, "method": "setRotation", "args": [-math.pi / 2, 0, 0]})
        ops.append({"op": "call", "object": hand, "method": "setPosition",
                    "args": [(i % columns) * GRID, 3, (i // columns) * GRID]})
    for k in range(objects):
        item = f"{client}.o{k}"
        ops.append({"op": "create", "object": item, "type": "Ball" if k % 2 else "Box",
                    "args": [0.4] if k % 2 else [0.7, 0.7, 0.7]})
        ops.append({"op": "call", "object": item, "method": "setPosition",
                    "args": [(k % columns) * GRID + 1.5 * (k % 3 - 1), 4 + k % 5,
                             (k // columns % columns) * GRID - 2]})
    ops.append({"op": "call", "object": "scene", "method": "setPhysics", "args": ["dynamic"]})
    return ops
