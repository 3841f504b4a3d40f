"""How long a script waits to connect to a busy server: ``scenes`` scenes, each with hands
that a client animates at 60 Hz (every driver a process of its own, on the same two cores),
then the Python client connects, with its default wait, to a fresh scene and to one of the
busy ones. The seconds until its snapshot arrived: what a user's ``vp.connect`` costs when
the machine is loaded (the clients waited a fixed 10 s before; 60 s by default now).
"""

from __future__ import annotations

import time
from contextlib import ExitStack
from typing import Any

import virtual_prosthetics as vp

from tests.conftest import RunningServer

from .live import driving
from .stats import figure


def connect_seconds(running: RunningServer, scene: str) -> float:
    """From asking to connect to holding the scene's snapshot (the client's default wait)."""
    started = time.monotonic()
    session = vp.Session(running.ws, scene, role="viewer")
    elapsed = time.monotonic() - started
    session.close()
    return elapsed


def measure(running: RunningServer, scenes: int, hands: int, rounds: int,
            seconds: float) -> dict[str, Any]:
    """``rounds`` connections to fresh scenes and to a busy one while ``scenes`` scenes of
    ``hands`` hands each are animated (drivers give up after ``seconds``)."""
    with ExitStack() as drivers:
        for k in range(scenes):
            drivers.enter_context(driving(running, f"loaded{k}", "hands", hands, seconds))
        fresh = [connect_seconds(running, f"arrival{k}") for k in range(rounds)]
        busy = [connect_seconds(running, "loaded0") for _ in range(rounds)]
    return {"scenes": scenes, "hands": hands, "connect_fresh_s": figure(fresh),
            "connect_busy_s": figure(busy)}
