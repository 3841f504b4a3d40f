"""Virtual Prosthetics client: the 1.0 library's API, in Python, against a server.

    import virtual_prosthetics as vp
    vp.connect("ws://127.0.0.1:8000")
    robot = vp.Robot()
    robot.attach_chain(vp.MotorZ(-0.7, 0.7, 0, 0.2, 0.6), vp.EdgedFinger(1, 1, 0.1))
    vp.set_animation(lambda t: robot.set_angles(0.7 * math.sin(t)))
    vp.run(10)
"""

from typing import Any

from .errors import (ConnectionLost, ProtocolError, ServerError, ServerWarning, Timeout,
                     VPError)
from .objects import (AnthroPalm, AnthroThumb, Ball, Box, EdgedFinger, EdgedPalm, EdgedTip,
                      GLTFPart, Motor, MotorX, MotorY, MotorZ, Node, Part, RoundFinger,
                      RoundPalm, SceneMesh, Slider, Slot)
from .robots import AnthroHand, EdgedHand, ImportedRobot, RoundHand, Robot
from .recordings import Recording, start_recording, stop_recording
from .runtime import connect, get_time, run, set_animation
from .sensor import Sensor
from .session import Session, current_session
from .viewer_cell import ViewerCell
from .uploads import load_robot, upload_asset

# The names of 0.x, when a session was called a scene: scripts that use them keep working.
Scene = Session
current_scene = current_session


def set_camera_position(*position: float) -> None:
    """Manual ``setCameraPosition(x, y, z)``: every viewer's camera moves there."""
    current_session().set_camera_position(*position)


def set_transforms(transforms: dict[Any, list[float]]) -> None:
    """Place many objects in one request (see :meth:`Session.set_transforms`)."""
    current_session().set_transforms(transforms)


def set_physics(mode: str, **options: float) -> None:
    """``vp.set_physics("dynamic", unit=0.19 / 3.5, gravity=9.81, substeps=5,
    solver_iterations=50, solver_tolerance=0.05, friction=1.0, density=1240, warm_start=0)`` or
    ``vp.set_physics("kinematic")`` (not in the manual; ``unit``: metres per scene unit)."""
    current_session().set_physics(mode, **options)


def get_physics() -> dict[str, Any]:
    """The scene's physics mode and options."""
    return current_session().get_physics()


def pause() -> None:
    """Stop the current scene's clock until ``resume`` (see :meth:`Session.pause`)."""
    current_session().pause()


def resume() -> None:
    """Let the current scene's clock run again (see :meth:`Session.resume`)."""
    current_session().resume()


def step(ticks: int = 1) -> float:
    """Advance the paused scene by ``ticks`` ticks; its time (see :meth:`Session.step`)."""
    return current_session().step(ticks)


def save_state() -> str:
    """Keep the current scene's state on the server; its id (:meth:`Session.save_state`)."""
    return current_session().save_state()


def restore_state(state: str) -> None:
    """Put the current scene back as ``state`` was (:meth:`Session.restore_state`)."""
    current_session().restore_state(state)


def forget_state(state: str) -> None:
    """Free a saved state (:meth:`Session.forget_state`)."""
    current_session().forget_state(state)


def show(width: int = 800, height: int = 500, role: str = "viewer") -> ViewerCell:
    """The current scene's live viewer for a notebook cell (:meth:`Session.show`)."""
    return current_session().show(width, height, role)


def set_camera_target(*target: float) -> None:
    """Manual ``setCameraTarget(x, y, z)``: every viewer's camera turns towards it."""
    current_session().set_camera_target(*target)


def set_caption(text: str) -> None:
    """Words every viewer of the current scene shows in a corner (:meth:`Session.set_caption`)."""
    current_session().set_caption(text)


__all__ = [
    "AnthroHand", "AnthroPalm", "AnthroThumb", "GLTFPart", "RoundFinger", "RoundHand",
    "RoundPalm", "Ball", "Box", "ConnectionLost", "EdgedFinger", "EdgedHand", "EdgedPalm", "EdgedTip",
    "Motor", "MotorX", "MotorY", "MotorZ", "Node", "Part", "Robot", "Scene", "Session", "Sensor", "Slider",
    "ProtocolError", "ServerError", "ServerWarning", "Slot", "Timeout", "VPError", "connect", "current_scene", "current_session", "get_time", "run",
    "set_animation", "set_camera_position", "set_camera_target", "set_caption", "set_transforms", "SceneMesh", "upload_asset", "ImportedRobot", "load_robot",
    "set_physics", "get_physics", "pause", "resume", "step", "save_state", "restore_state", "forget_state", "show", "Recording", "start_recording", "stop_recording",
]
