"""The environments' action: one value in [-1, 1] per motor, in motor order.

``control="angles"`` (the default): -1 and 1 are the ends of the motor's range, the
motor's own limits where it has them, else its way from open to closed in the grip map,
else a quarter turn either side of its angle as made; the motor drives there with its torque
bound. ``control="torques"``: the motor drives with that share of its torque bound,
towards its upper limit when positive (:class:`~..tasks.observation.Torques`).

A motor that follows another (a coupled joint, ``follow``) takes the value it is given
(the server ignores a follower's own targets: its leader moves it)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from gymnasium import spaces

from ..codec import from_wire
from ..robots import Robot
from ..tasks.grip import HandGrip
from ..tasks.observation import Angles, Targets, Torques

CONTROLS = ("angles", "torques")


@dataclass(frozen=True)
class ActionMap:
    """How an action becomes a hand's motor targets."""

    control: str
    ranges: tuple[tuple[float, float], ...]  # each motor's angle at -1 and at 1
    torques: tuple[float, ...]               # each motor's torque bound (N·m)

    def space(self) -> spaces.Box:
        return spaces.Box(-1.0, 1.0, shape=(len(self.ranges),), dtype=np.float32)

    def targets(self, action: np.ndarray) -> Targets:
        """The motor targets of ``action`` (clipped to [-1, 1])."""
        values = np.clip(np.asarray(action, dtype=np.float64), -1.0, 1.0)
        if self.control == "torques":
            return Torques([float(v) * bound for v, bound in zip(values, self.torques)])
        return Angles([low + (float(v) + 1) / 2 * (high - low) for v, (low, high) in zip(values, self.ranges)])

    def action_of(self, angles: list[float]) -> np.ndarray:
        """The action (angles control) that asks for ``angles``."""
        return np.array([2 * (a - low) / (high - low) - 1 if high > low else 0.0
                         for a, (low, high) in zip(angles, self.ranges)], dtype=np.float32)


def action_map(hand: Robot, grip: HandGrip, control: str) -> ActionMap:
    """The action map of ``hand`` gripping by ``grip``."""
    if control not in CONTROLS:
        raise ValueError(f"control {control!r}: expected one of {', '.join(CONTROLS)}")
    spans = {m.index: (m.open, m.closed) for d in grip.digits for m in (*d.motors, *d.preshape)}
    ranges, torques = [], []
    for index, motor in enumerate(hand.get_motors()):
        state = motor._state()
        low, high = from_wire(state["min"]), from_wire(state["max"])
        if not (math.isfinite(low) and math.isfinite(high)):
            low, high = sorted(spans.get(index, (state["angle"] - math.pi / 2, state["angle"] + math.pi / 2)))
        ranges.append((float(low), float(high)))
        torques.append(float(state["maxTorque"]))
    return ActionMap(control, tuple(ranges), tuple(torques))
