"""The client's runtime, as the JS client's runtime.js: ``connect``, the class of every
type (for objects this client did not make) and the manual's animation loop."""

from __future__ import annotations

import inspect
import time
from typing import Callable

from . import objects
from . import session as sessions
from .errors import ConnectionLost, ServerError
from .objects import Node
from .robots import AnthroHand, EdgedHand, ImportedRobot, Robot, RoundHand
from .session import Session, current_session, set_current_session
from .sensor import Sensor

# The class of every type (a scene makes objects of them for ids this client did not make).
CLASSES: dict[str, type[Node]] = {cls._type: cls for cls in (
    objects.Slot, objects.Part, objects.Motor, objects.Slider, objects.MotorX, objects.MotorY, objects.MotorZ,
    objects.Ball, objects.Box, objects.EdgedFinger, objects.EdgedTip, objects.EdgedPalm,
    objects.GLTFPart, objects.RoundFinger, objects.RoundPalm, objects.AnthroPalm,
    objects.AnthroThumb, objects.SceneMesh, Sensor, Robot, EdgedHand, RoundHand, AnthroHand,
    ImportedRobot)}
sessions.CLASSES.update(CLASSES, Node=Node, RobotLink=objects.Part)  # links: made by their robot


def connect(url: str = "ws://127.0.0.1:8000", scene: str = "default",
            role: str = "controller", token: str | None = None, keep: bool = False,
            timeout: float | None = None) -> Session:
    """Connect to a scene of a server and make it the current scene; ``token`` (default:
    the ``VP_TOKEN`` environment variable) when the server asks for one; ``keep``: what
    this script makes stays in the scene after it ends; ``timeout``: seconds to wait for
    the scene and for each answer (default: the ``VP_TIMEOUT`` environment variable, else
    60)."""
    opened = Session(url, scene, role, token=token, keep=keep, timeout=timeout)
    set_current_session(opened)
    return opened


def set_animation(func: Callable[..., None], fps: float = 30) -> None:
    """Manual ``setAnimation(func, fps=30)``: ``func(time, dtime)`` runs ``fps`` times a second."""
    if fps <= 0:
        raise ValueError(f"fps must be positive, got {fps}")
    current_session().animation = (func, fps)


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
    What a step sends nobody waits for reaches the server as one batch, applied as one
    and answered once (a refused call undoes the step's others; the next call raises it;
    a read in the step sends what came before it first). In a scene this client paused
    (``pause``), each step is followed by the ticks of one period (``step``), without
    waiting: the animation comes out the same on every run and as fast as the server
    computes it.
    """
    scene = current_session()
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
            with scene.connection.gathering():  # the step's setters leave as one batch
                func(*(now, step)[:arity])
        last = now
        if scene.holding and _stepped(scene, max(1, round(period * scene.tick_rate))):
            continue
        next_wake = max(next_wake + period, time.monotonic())
        time.sleep(max(0.0, next_wake - time.monotonic()))
    scene.sync()


def _stepped(scene: sessions.Session, ticks: int) -> bool:
    """Step the scene this client holds; False when the pause is gone (the animation
    then runs on with the wall clock)."""
    try:
        scene.step(ticks)
    except ServerError as error:
        if error.code != "not_paused":
            raise
        return False
    return True


def get_time() -> float:
    """Manual ``getTime()``: the current scene's server time."""
    return current_session().get_time()
