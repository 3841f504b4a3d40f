"""The Python client's mirror: its clock (the time ``get_time`` and ``run`` give)."""

from __future__ import annotations

from typing import Any

from virtual_prosthetics.mirror import Mirror


class Clock:
    """A monotonic clock the test moves by hand."""

    def __init__(self) -> None:
        self.value = 100.0

    def __call__(self) -> float:
        return self.value


def _frame(time: float, seq: int) -> dict[str, Any]:
    return {"op": "frame", "time": time, "seq": seq}


def _snapshot(time: float) -> dict[str, Any]:
    return {"op": "snapshot", "time": time, "seq": 0, "camera": {}, "nodes": [],
            "contacts": [], "physics": {"mode": "kinematic"}}


def test_time_runs_on_between_frames() -> None:
    clock = Clock()
    mirror = Mirror(clock=clock)
    mirror.apply(_snapshot(5.0))
    clock.value += 0.25
    assert mirror.now() == 5.25


def test_a_frame_that_comes_late_never_turns_time_back() -> None:
    # Seen in CI: an animation was handed 0.124 then 0.117 when a frame was delayed.
    # (Binary fractions keep the sums exact.)
    clock = Clock()
    mirror = Mirror(clock=clock)
    mirror.apply(_snapshot(1.0))
    clock.value += 0.25
    assert mirror.now() == 1.25
    mirror.apply(_frame(1.125, 1))         # sent at 1.125, read only now
    assert mirror.now() == 1.25
    clock.value += 0.0625
    assert mirror.now() == 1.25            # still behind what was already given
    clock.value += 0.125
    assert mirror.now() == 1.3125          # and on from the frame once past it


def test_a_new_snapshot_may_start_the_clock_again() -> None:
    # A server restarted from its state folder counts the scene's time from 0 again.
    clock = Clock()
    mirror = Mirror(clock=clock)
    mirror.apply(_snapshot(30.0))
    clock.value += 1
    assert mirror.now() == 31.0
    mirror.apply(_snapshot(0.5))
    assert mirror.now() == 0.5


def test_the_physics_and_the_forces_on_parts_follow_the_frames() -> None:
    mirror = Mirror()
    mirror.apply(_snapshot(0.0))
    dynamic = {"mode": "dynamic", "gravity": 9.81}
    mirror.apply({"op": "frame", "seq": 1, "time": 0.1, "physics": dynamic, "forces": {"c1.b": 98.1}})
    assert mirror.physics == dynamic and mirror.forces == {"c1.b": 98.1}
    mirror.apply({"op": "frame", "seq": 2, "time": 0.2, "forces": {"c1.b": 0, "c1.f": 3.5}})
    assert mirror.forces == {"c1.f": 3.5}  # 0: its contacts ended


def test_a_snapshot_replaces_the_sensors_readings() -> None:
    """A reading from before a snapshot is of a world that may be gone (a restored scene's
    sensor would read its last episode's contacts)."""
    mirror = Mirror()
    mirror.apply(_snapshot(0.0))
    pressed = {"distance": 0.5, "touch": 1, "position": [0, 0, 0], "objects": ["c1.b"],
               "force": 3.0, "contacts": [{"other": "c1.b", "normal": 3.0, "friction": 0.0}]}
    mirror.apply({"op": "frame", "seq": 1, "time": 0.1, "sensors": {"c1.s": pressed, "c1.t": pressed}})
    free = {**pressed, "distance": "Infinity", "touch": 0, "objects": [], "force": 0, "contacts": []}
    mirror.apply({**_snapshot(0.0), "sensors": {"c1.s": free}})
    assert mirror.readings["c1.s"]["contacts"] == [] and mirror.readings["c1.s"]["distance"] == float("inf")
    assert "c1.t" not in mirror.readings  # not watched in the new world: nothing told
