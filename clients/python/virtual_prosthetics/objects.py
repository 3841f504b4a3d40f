"""The manual's classes, in Python: each object stands for one object on the server.

Constructors and methods take the manual's arguments in the manual's order; a left-out
argument (None) takes the server's default. Names are the manual's in snake_case.
"""

from __future__ import annotations

from typing import Any, Callable, ClassVar

from .codec import from_wire
from .errors import VPError
from .session import Session, current_session


class Node:
    """Base of every scene object: its ``id`` and the scene it lives in."""

    _type: ClassVar[str] = ""
    id: str
    _scene: Session

    @classmethod
    def stand_in(cls, scene: Session, node_id: str) -> Node:
        """An object of this class for an id this client did not make (a hand's parts,
        another client's objects): no creation is sent."""
        obj = cls.__new__(cls)
        obj._scene, obj.id = scene, node_id
        return obj

    def _create(self, scene: Session | None, *args: Any) -> None:
        self._scene = scene if scene is not None else current_session()
        self.id = self._scene.new_id()
        self._scene.create(self, self._type, args)

    def _call(self, method: str, *args: Any) -> None:
        self._scene.call(self.id, method, args)

    def _state(self) -> dict[str, Any]:
        node = self._scene.read(lambda mirror: mirror.nodes.get(self.id))
        if node is None:
            raise VPError(f"{self.id} is not in the scene (deleted, or its creation failed)")
        return node

    def delete(self) -> None:
        """Remove the object (and what is attached below it) from the scene."""
        self._scene.delete(self.id)

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {getattr(self, 'id', '?')}>"


class Posed(Node):
    """An object with a settable position and rotation relative to its parent."""

    def set_position(self, *position: Any) -> None:
        """Manual ``setPosition([x, y, z])`` or ``setPosition(x, y, z)``."""
        self._call("setPosition", *position)

    def set_rotation(self, x: float, y: float, z: float, order: str = "XYZ") -> None:
        """Manual ``setRotation(x, y, z, order='XYZ')``: Euler angles."""
        self._call("setRotation", x, y, z, order)

    def set_quaternion(self, quaternion: list[float]) -> None:
        """The rotation as a quaternion [x, y, z, w] (not in the manual; normalised)."""
        self._call("setQuaternion", list(quaternion))

    def set_scale(self, scale: list[float]) -> None:
        """Stretch the object and what hangs below it, [x, y, z] (three.js ``scale``)."""
        self._call("setScale", list(scale))


class Shown(Posed):
    """An object that can be hidden (three.js ``visible``)."""

    def set_visible(self, visible: bool) -> None:
        """Draw the object or not (a hidden part is still sensed; a hidden robot is out
        of the scene)."""
        self._call("setVisible", visible)

    def keep(self, on: bool = True) -> Shown:
        """Leave the object (and what hangs below it) in the scene when this script's
        connection ends (not in the manual; ``connect(keep=True)`` keeps everything)."""
        self._call("keep", on)
        return self


class Slot(Posed):
    """Manual ``Slot()``, ``Slot([x, y, z])`` or ``Slot(x, y, z)``."""

    _type = "Slot"

    def __init__(self, *position: Any, scene: Session | None = None) -> None:
        self._create(scene, *position)


class Part(Shown):
    """Manual ``Part``: the base of every robot part (invisible, no shape)."""

    _type = "Part"

    def __init__(self, *, scene: Session | None = None) -> None:
        self._create(scene)

    def add_slot(self, *position: Any) -> Slot:
        """Manual ``addSlot(x, y, z)``: a new slot on this part (waits for the server)."""
        result = self._scene.call(self.id, "addSlot", position, wait=True)
        return self._scene.proxy(result["ref"])  # type: ignore[return-value]

    def attach_to_slot(self, parent: Node, slot: int | Slot = 0) -> Part:
        """Manual ``attachToSlot(parent, slot=0)``; returns this part."""
        self._call("attachToSlot", parent, slot)
        return self

    # --- dynamic mode (not in the manual) ---------------------------------------------

    def set_mass(self, mass: float) -> Part:
        """Its mass in kilograms in dynamic mode (instead of volume × the scene's density);
        returns this part."""
        self._call("setMass", mass)
        return self

    def get_mass(self) -> float:
        """Its mass in dynamic mode (kg; asks the server: a mass from the volume depends
        on the scales above the part)."""
        return float(self._scene.call(self.id, "getMass", (), wait=True))

    def set_friction(self, friction: float) -> Part:
        """Its friction coefficient in dynamic mode (instead of the scene's); returns it."""
        self._call("setFriction", friction)
        return self

    def set_static(self, static: bool = True) -> Part:
        """At the top of its tree: never moves in dynamic mode (a table); returns it."""
        self._call("setStatic", static)
        return self

    @property
    def hears_contacts(self) -> bool:
        """True when a subclass overrides ``begin_contact`` or ``end_contact`` (only then
        does the client keep this part's contact changes for them)."""
        cls = type(self)
        return cls.begin_contact is not Part.begin_contact or cls.end_contact is not Part.end_contact

    def begin_contact(self, other: Node) -> None:
        """Manual ``beginContact(otherPart)``: override to react to a new contact."""

    def end_contact(self, other: Node) -> None:
        """Manual ``endContact(otherPart)``: override to react to a lost contact."""


class Motor(Part):
    """Manual ``Motor(axis, min=-Infinity, max=Infinity, def=0)``."""

    _type = "Motor"

    def __init__(self, axis: str, min: float | None = None, max: float | None = None,
                 default: float | None = None, *, scene: Session | None = None) -> None:
        self._create(scene, axis, min, max, default)

    def set_name(self, name: str) -> Motor:
        """Manual ``setName(name)``; returns the motor."""
        self._call("setName", name)
        return self

    def get_angle(self) -> float:
        """Manual ``getAngle()``."""
        return self._state()["angle"]

    def get_name(self) -> str | None:
        """The name ``set_name`` gave it (an imported joint's: the file's), or None."""
        return self._state().get("name")

    def set_angle(self, angle: float | None) -> None:
        """Manual ``setAngle(angle)``: None and NaN are ignored, the rest clamped. In
        dynamic mode the motor drives there; ``get_angle`` reads where it is."""
        self._call("setAngle", angle)

    def set_max_torque(self, torque: float) -> Motor:
        """The most torque (N·m) it drives with in dynamic mode; returns the motor."""
        self._call("setMaxTorque", torque)
        return self

    def get_max_torque(self) -> float:
        """Its torque bound in dynamic mode (N·m)."""
        return float(self._state()["maxTorque"])

    def set_max_speed(self, speed: float) -> Motor:
        """The fastest it moves in dynamic mode (rad/s; a slider's scene units/s), as a
        servo's rated speed (``math.inf``, the default: no limit); returns the motor."""
        self._call("setMaxSpeed", speed)
        return self

    def get_max_speed(self) -> float:
        """Its speed bound in dynamic mode (``math.inf``: none)."""
        return float(from_wire(self._state().get("maxSpeed", "Infinity")))

    def get_torque(self) -> float:
        """The torque it drove with in the last step (N·m; a slider's force, N), positive
        pushing its angle up: what a servo's current tells (dynamic mode; 0 in kinematic
        mode). Asks the server."""
        return float(from_wire(self._scene.call(self.id, "getTorque", (), wait=True)))

    def get_speed(self) -> float:
        """How fast it turned at the last step (rad/s; a slider's scene units/s), positive
        turning its angle up (dynamic mode; 0 in kinematic mode). Asks the server."""
        return float(from_wire(self._scene.call(self.id, "getSpeed", (), wait=True)))

    def follow(self, leader: Motor | None = None, ratio: float = 1.0,
               offset: float = 0.0) -> Motor:
        """Turn with the motor ``leader``: whenever it is set to ``a``,
        this motor goes to ``ratio·a + offset`` in the same tick, as a linkage or tendon
        couples joints; its own ``set_angle`` is then ignored. ``follow()`` frees it.
        Returns the motor."""
        self._call("follow", leader, ratio, offset)
        return self

    def flip(self, flipped: bool = True) -> Motor:
        """Manual ``flip(bool)``: turn the other way; returns the motor."""
        self._call("flip", flipped)
        return self


class Slider(Motor):
    """Not in 1.0: ``Slider(axis, min, max, def)``, a motor that slides along its axis (a
    linear actuator, an imported prismatic joint). Its angle, min and max are lengths in
    scene units; ``set_max_torque`` sets its force bound (N)."""

    _type = "Slider"


class _AxisMotor(Motor):
    def __init__(self, min: float | None = None, max: float | None = None,
                 default: float | None = None, width: float | None = None,
                 height: float | None = None, *, scene: Session | None = None) -> None:
        self._create(scene, min, max, default, width, height)


class MotorX(_AxisMotor):
    """Manual ``MotorX(min, max, def, width=0.1, height=0.05)``."""

    _type = "MotorX"


class MotorY(_AxisMotor):
    """Manual ``MotorY(min, max, def, width=0.3, height=0.05)``."""

    _type = "MotorY"


class MotorZ(_AxisMotor):
    """Manual ``MotorZ(min, max, def, width=0.1, height=0.05)``."""

    _type = "MotorZ"


class Ball(Part):
    """Manual ``Ball(radius=1, color='dimgray')``."""

    _type = "Ball"

    def __init__(self, radius: float | None = None, color: str | int | None = None, *,
                 scene: Session | None = None) -> None:
        self._create(scene, radius, color)


class Box(Part):
    """Manual ``Box(sizex=1, sizey=1, sizez=1, color='dimgray')``."""

    _type = "Box"

    def __init__(self, sizex: float | None = None, sizey: float | None = None,
                 sizez: float | None = None, color: str | int | None = None, *,
                 scene: Session | None = None) -> None:
        self._create(scene, sizex, sizey, sizez, color)


class SceneMesh(Part):
    """A mesh of its own geometry, as a page adds one to its scene (not in the manual):
    ``SceneMesh({"kind": "box", "size": [1, 2, 1]}, "red")``; the kinds are box, sphere,
    cylinder, hull and triangles (see the protocol's README)."""

    _type = "SceneMesh"

    def __init__(self, geometry: dict[str, Any], color: str | int | None = None, *,
                 scene: Session | None = None) -> None:
        self._create(scene, geometry, color)

    def set_color(self, color: str | int) -> None:
        """The colour every viewer draws the shape in."""
        self._call("setColor", color)


class EdgedFinger(Part):
    """Manual ``EdgedFinger(length=1, width=0.3, thickness=0.3)``."""

    _type = "EdgedFinger"

    def __init__(self, length: float | None = None, width: float | None = None,
                 thickness: float | None = None, *, scene: Session | None = None) -> None:
        self._create(scene, length, width, thickness)


class EdgedTip(EdgedFinger):
    """Manual ``EdgedTip(length=1, width=0.3, thickness=0.3)``."""

    _type = "EdgedTip"


class EdgedPalm(Part):
    """Manual ``EdgedPalm(left, length=1.4, width=1.4, thickness=0.3)``."""

    _type = "EdgedPalm"

    def __init__(self, left: bool | None = None, length: float | None = None,
                 width: float | None = None, thickness: float | None = None, *,
                 scene: Session | None = None) -> None:
        self._create(scene, left, length, width, thickness)


Color = Any  # a CSS colour name, "#hex", 0xRRGGBB or [r, g, b] in 0…1


class GLTFPart(Part):
    """Manual ``GLTFPart(filename, length=0, callback)``: a part shaped by a mesh file.

    ``callback(part)`` runs once the server has made the part (as 1.0 ran it once the
    file had loaded); it is keyword-only here.
    """

    _type = "GLTFPart"

    def __init__(self, filename: str, length: float | None = None, *,
                 callback: Callable[[GLTFPart], Any] | None = None,
                 scene: Session | None = None) -> None:
        self._create(scene, filename, length)
        self._ready(callback)

    def _ready(self, callback: Callable[[GLTFPart], Any] | None) -> None:
        if callback is not None:
            self._scene.sync()  # raises the server's error when the part was not made
            callback(self)

    def recolor(self, from_color: Color, to_color: Color, eps: float | None = None) -> None:
        """Manual ``recolor(fromColor, toColor, eps=0.01)``: in every viewer, now and later."""
        self._call("recolor", from_color, to_color, eps)


class RoundFinger(GLTFPart):
    """Manual ``RoundFinger(filename, length=0.8)``: one slot at (0, length, 0)."""

    _type = "RoundFinger"


class _HandedPart(GLTFPart):
    """A mesh part made for a left or a right hand (the right one mirrored in X)."""

    def __init__(self, left: bool, filename: str, length: float | None = None, *,
                 callback: Callable[[GLTFPart], Any] | None = None,
                 scene: Session | None = None) -> None:
        self._create(scene, left, filename, length)
        self._ready(callback)


class RoundPalm(_HandedPart):
    """Manual ``RoundPalm(left, filename, length=1.4)``: five finger slots, the thumb's first."""

    _type = "RoundPalm"


class AnthroPalm(_HandedPart):
    """Manual ``AnthroPalm(left, filename, length=1.4)``: the round palm cut for the thumb."""

    _type = "AnthroPalm"


class AnthroThumb(_HandedPart):
    """Manual ``AnthroThumb(left, filename, length=1.4)``: one slot for its finger."""

    _type = "AnthroThumb"
