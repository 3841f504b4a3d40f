"""The manual's animation loop: ``set_animation(func, fps)`` then ``run()``."""

from __future__ import annotations

import inspect
import time
from typing import Callable

from .errors import ConnectionLost
from .scene import current_scene


def set_animation(func: Callable[..., None], fps: float = 30) -> None:
    """Manual ``setAnimation(func, fps=30)``: ``func(time, dtime)`` runs ``fps`` times a second."""
    if fps <= 0:
        raise ValueError(f"fps must be positive, got {fps}")
    current_scene().animation = (func, fps)


def _arity(func: Callable[..., None]) -> int:
    try:
        parameters = inspect.signature(func).parameters.values()
    except (TypeError, ValueError):
        return 2
    if any(p.kind is p.VAR_POSITIONAL for p in parameters):
        return 2
    return min(2, sum(p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) for p in parameters))


def run(seconds: float | None = None) -> None:
    """Run the animation for ``seconds`` of server time, or until the connection closes
    (across a server restart too, whose clock begins again).

    Before every step the contact callbacks that are due run (``begin_contact`` and
    ``end_contact`` of this client's parts). Without an animation, ``run`` only does that.
    """
    scene = current_scene()
    func, fps = scene.animation or (None, 30.0)
    arity, period = _arity(func) if func else 0, 1.0 / fps
    last, elapsed = scene.get_time(), 0.0
    next_wake = time.monotonic()
    while seconds is None or elapsed < seconds:
        if scene.connection.closed is not None:
            raise ConnectionLost(scene.connection.closed)
        scene.dispatch_contacts()
        now = scene.get_time()
        step = max(0.0, now - last)  # a server restarted from its state folder counts from 0
        elapsed += step
        if func is not None:
            func(*(now, step)[:arity])
        last = now
        next_wake = max(next_wake + period, time.monotonic())
        time.sleep(max(0.0, next_wake - time.monotonic()))
    scene.sync()


def get_time() -> float:
    """Manual ``getTime()``: the current scene's server time."""
    return current_scene().get_time()
