"""The API table: every type, constructor and method a client may use, in one place.

Names are the manual's (camelCase, as on the wire and in the JavaScript client); the
Python name of each method is derived by :func:`snake`. ``protocol/api.json`` is this
table exported for the clients (``make generate``: generate/api_table.py); a test fails when
it drifts.

Parameter kinds (how each argument is checked, see :mod:`server.core.protocol.arguments`):
``number`` finite number · ``size`` 0.001 to 1000 (metres) · ``integer`` whole number ·
``limit`` number or ±Infinity · ``angle`` number, ±Infinity (clamped), null or NaN
(ignored) · ``bool`` · ``string`` · ``color`` CSS colour name, #hex or 0xRRGGBB number ·
``axis`` 'x', 'y' or 'z' · ``order`` an Euler order · ``point`` [x, y, z] or x, y, z, each
within ±100 000 ·
``node`` a robot or part reference · ``part`` a part reference · ``slot`` slot index or
Slot reference · ``laser`` a colour, true (crimson), false or null (no laser) · ``rgb`` a colour or
[r, g, b] in 0…1 · ``asset`` a mesh filename (bundled or uploaded) ·
``contact`` a part reference or "ground" · ``quaternion`` [x, y, z, w], not of zero length
(normalised) · ``scale`` [x, y, z], each 0 to 1000 · ``geometry`` a SceneMesh's geometry
(:mod:`server.core.physics.geometry`) · ``transforms`` {id: [px, py, pz, qx, qy, qz, qw] with
sx, sy, sz optionally after} · ``mode`` 'kinematic' or 'dynamic' · ``options`` an object of
physics options (checked by :class:`server.core.physics.settings.Physics`) · ``mass`` kg,
above 0, at most 1e9 · ``friction`` 0 to 10 · ``torque`` N·m, 0 to 1e12 · ``speed`` above 0 (rad/s; a slider's scene units/s) or
Infinity (no limit) · ``ticks`` a whole number of ticks, 1 to 60.

Return kinds: ``none`` · ``self`` the object · ``ref``/``refs`` objects · ``ids`` objects
or "ground" as references · ``number``/``numbers`` · ``bool`` · ``point`` [x, y, z] ·
``physics`` the scene's physics (``{"mode", "gravity", …}``) · ``contacts`` what presses
on a part, ``[{"other", "normal", "friction"}, …]`` (N) · ``gripMap`` a hand's digits
(the schema's ``gripMap``) · ``name`` a string or null.
A method marked ``client`` is handed the calling client's id (``watch`` is per client).
"""

from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass, field
from typing import Any, Mapping

from ..kit.math3d import ORIGIN
from ..model import part_figures

REQUIRED: Any = type("Required", (), {"__repr__": lambda self: "REQUIRED"})()


def snake(name: str) -> str:
    """The Python name of a manual name: ``attachToSlot`` → ``attach_to_slot``, ``addGUI`` → ``add_gui``."""
    return re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", name).lower()


@dataclass(frozen=True)
class Param:
    """One parameter: its name in the manual, its kind, its default, whether it repeats."""

    name: str
    kind: str
    default: Any = REQUIRED
    variadic: bool = False
    # a node the call attaches to, which may be another client's shared robot (a
    # repeated parameter: its first item only); every other node a change names is the caller's
    destination: bool = False


@dataclass(frozen=True)
class Method:
    """One method of a type as the manual names it."""

    name: str
    params: tuple[Param, ...] = ()
    returns: str = "none"
    mutates: bool = True
    client: bool = False
    # who may call it on another client's robot once shared (server.core.protocol.ownership):
    # "owner" nobody else, "steer" anyone (motor angles), "attach" anyone, with their own parts;
    # on the scene, "keeper": only the client whose scene it is, or one with the control token
    access: str = "owner"

    @functools.cached_property
    def python(self) -> str:
        """The method's name in Python (the server core and the Python client)."""
        return snake(self.name)


@dataclass(frozen=True)
class TypeSpec:
    """A type: its base type, constructor parameters, own methods and client callbacks."""

    name: str
    base: str | None
    params: tuple[Param, ...] = ()
    methods: tuple[Method, ...] = ()
    creatable: bool = True
    callbacks: tuple[str, ...] = field(default=())
    slots: int = 0  # numbered slots a new object has (ids <id>/s0 …), so that a client can
    # name the one addSlot makes next without waiting for the answer


def _sizes(*names_defaults: tuple[str, float]) -> tuple[Param, ...]:
    return tuple(Param(name, "size", default) for name, default in names_defaults)


def _motor_params(motor: str) -> tuple[Param, ...]:
    figure = part_figures.MOTORS[motor]
    return (Param("min", "limit", -math.inf), Param("max", "limit", math.inf),
            Param("def", "number", 0.0), *_sizes(("width", figure.width),
                                                ("height", figure.height)))


def _edged(defaults: dict[str, float]) -> tuple[Param, ...]:
    return _sizes(*defaults.items())


POSITION = Method("setPosition", (Param("position", "point"),))
ROTATION = Method("setRotation", (Param("x", "number"), Param("y", "number"),
                                  Param("z", "number"), Param("order", "order", "XYZ")))
# not in the manual: how the JavaScript client sends a rotation a page wrote to an
# object's `quaternion` or `rotation` directly (three.js style)
QUATERNION = Method("setQuaternion", (Param("quaternion", "quaternion"),))
# not in the manual either: three.js `scale` and `visible`, written directly by pages
SCALE = Method("setScale", (Param("scale", "scale"),))
VISIBLE = Method("setVisible", (Param("visible", "bool"),))
# not in the manual: what stays in the scene when its owner leaves (server.core.protocol.session)
KEEP = Method("keep", (Param("on", "bool", True),), returns="self")
HAND_METHODS = (
    Method("flexFinger", (Param("index", "integer"), Param("angle", "angle")), access="steer"),
    Method("flexFingers", (Param("angle", "angle"),), access="steer"),
    Method("spreadFinger", (Param("index", "integer"), Param("angle", "angle")), access="steer"),
    Method("spreadFingers", (Param("angle", "number"), Param("includeThumb", "bool", False)),
           access="steer"),
)

TYPES: dict[str, TypeSpec] = {t.name: t for t in (
    TypeSpec("Scene", None, creatable=False, methods=(
        Method("setCameraPosition", (Param("position", "point"),)),
        Method("setCameraTarget", (Param("target", "point"),)),
        # not in the manual: words every viewer shows in a corner (server.core.scene.caption)
        Method("setCaption", (Param("text", "string"),)),
        Method("getTime", returns="number", mutates=False),
        Method("setTransforms", (Param("transforms", "transforms"),)),
        # not in the manual: dynamic mode (server.core.physics.dynamics)
        Method("setPhysics", (Param("mode", "mode"), Param("options", "options", None)),
               access="keeper"),
        Method("getPhysics", returns="physics", mutates=False),
        # not in the manual: a script's own clock (server.core.scene.clock)
        Method("pause", client=True),
        Method("resume"),
        Method("step", (Param("ticks", "ticks", 1),)),
        # not in the manual: the scene's state kept and put back (server.core.protocol.saved_states)
        Method("saveState", returns="string"),
        Method("restoreState", (Param("state", "string"),), access="keeper"),
        Method("forgetState", (Param("state", "string"),)),
        # not in the manual: recordings (server.core.recording), kept by the server
        Method("startRecording", client=True, returns="string"),
        Method("stopRecording", returns="recording"),
    )),
    TypeSpec("Slot", None, (Param("position", "point", ORIGIN),),
             (POSITION, ROTATION, QUATERNION, SCALE)),
    TypeSpec("Part", None, methods=(
        Method("addSlot", (Param("position", "point", ORIGIN),), returns="ref"),
        Method("attachToSlot", (Param("parent", "node", destination=True),
                                Param("slot", "slot", 0, destination=True)), returns="self"),
        POSITION, ROTATION, QUATERNION, SCALE, VISIBLE, KEEP,
        # not in the manual: a part's body in dynamic mode (server.core.physics.dynamics)
        Method("setMass", (Param("mass", "mass"),), returns="self"),
        Method("getMass", returns="number", mutates=False),
        Method("setFriction", (Param("friction", "friction"),), returns="self"),
        Method("setStatic", (Param("static", "bool", True),), returns="self"),
    ), callbacks=("beginContact", "endContact")),
    TypeSpec("Motor", "Part", (Param("axis", "axis"), Param("min", "limit", -math.inf),
                               Param("max", "limit", math.inf), Param("def", "number", 0.0)),
             (Method("setName", (Param("name", "string"),), returns="self"),
              # not in the manual: the name setName gave (an imported joint's), or null
              Method("getName", returns="name", mutates=False),
              Method("getAngle", returns="number", mutates=False),
              Method("setAngle", (Param("angle", "angle"),), access="steer"),
              Method("flip", (Param("bool", "bool", True),), returns="self"),
              # not in the manual: what the motor drives with in dynamic mode
              Method("setMaxTorque", (Param("torque", "torque"),), returns="self"),
              Method("getMaxTorque", returns="number", mutates=False),
              Method("setMaxSpeed", (Param("speed", "speed"),), returns="self"),
              Method("getMaxSpeed", returns="number", mutates=False),
              # the torque it drove with in the last step, as a servo's current tells
              Method("getTorque", returns="number", mutates=False),
              Method("getSpeed", returns="number", mutates=False),
              # not in the manual: coupled joints (a linkage, a tendon; URDF <mimic>)
              Method("follow", (Param("leader", "motor", None), Param("ratio", "number", 1.0),
                                Param("offset", "number", 0.0)), returns="self"))),
    # not in the manual: a motor that slides along its axis (a linear actuator, an imported
    # prismatic joint); its value and limits are lengths, its bound a force (N)
    TypeSpec("Slider", "Motor", (Param("axis", "axis"), Param("min", "limit", -math.inf),
                                 Param("max", "limit", math.inf), Param("def", "number", 0.0))),
    TypeSpec("MotorX", "Motor", _motor_params("MotorX"), slots=1),
    TypeSpec("MotorY", "Motor", _motor_params("MotorY"), slots=1),
    TypeSpec("MotorZ", "Motor", _motor_params("MotorZ"), slots=1),
    TypeSpec("Ball", "Part", (Param("radius", "size", 1.0),
                              Param("color", "color", part_figures.DEFAULT_COLOR))),
    TypeSpec("Box", "Part", (*_sizes(("sizex", 1.0), ("sizey", 1.0), ("sizez", 1.0)),
                             Param("color", "color", part_figures.DEFAULT_COLOR))),
    TypeSpec("EdgedFinger", "Part", _edged(part_figures.EDGED_FINGER_DEFAULTS), slots=1),
    TypeSpec("EdgedTip", "Part", _edged(part_figures.EDGED_FINGER_DEFAULTS), slots=1),
    TypeSpec("EdgedPalm", "Part", (Param("left", "bool", False),
                                   *_edged(part_figures.EDGED_PALM_DEFAULTS)), slots=5),
    TypeSpec("Sensor", "Part", (Param("visible", "bool", True),
                                Param("laserColor", "laser", None)), (
        Method("senseDistance", returns="number", mutates=False),
        Method("senseTouch", returns="number", mutates=False),
        Method("sensePosition", returns="point", mutates=False),
        Method("senseCollision", returns="bool", mutates=False),
        Method("senseObjects", returns="ids", mutates=False),
        Method("senseObject", (Param("otherObject", "contact"),), returns="bool",
               mutates=False),
        # not in the manual: newtons pressing on the sensor's part, from all or from one
        # other body, and each body's normal and friction forces (dynamic mode; else 0)
        Method("senseForce", (Param("otherObject", "contact", None),), returns="number",
               mutates=False),
        Method("senseContacts", returns="contacts", mutates=False),
        Method("watch", (Param("on", "bool", True),), mutates=False, client=True),
    )),
    TypeSpec("Robot", None, methods=(
        Method("attachChain", (Param("parts", "part", variadic=True),), returns="ref",
               access="attach"),
        Method("addChain", (Param("parts", "node", variadic=True, destination=True),),
               returns="ref", access="attach"),
        Method("addGUI", (Param("title", "string", "Robot"),)),
        Method("getParts", returns="refs", mutates=False),
        Method("getMotors", returns="refs", mutates=False),
        Method("getSensors", returns="refs", mutates=False),
        # not in the manual: the hand's digits and their motors, from its kinematics
        # (the hand-function tasks' baseline closes any hand by it)
        Method("getGripMap", returns="gripMap", mutates=False),
        Method("getPosition", returns="point", mutates=False),
        # 1.0 returns the robot from these two (pages chain them), not from a part's
        Method("setPosition", (Param("position", "point", None),), returns="self"),
        Method("setRotation", ROTATION.params, returns="self"),
        QUATERNION, SCALE, VISIBLE,
        Method("getAngle", (Param("index", "integer"),), returns="number", mutates=False),
        Method("setAngle", (Param("index", "integer"), Param("angle", "angle")), access="steer"),
        Method("getAngles", returns="numbers", mutates=False),
        # not in the manual: each motor's getSpeed and getTorque at once (a controller's
        # observation each step)
        Method("getSpeeds", returns="numbers", mutates=False),
        Method("getTorques", returns="numbers", mutates=False),
        Method("setAngles", (Param("angles", "angle", variadic=True),), access="steer"),
        # not in the manual: let other clients set this robot's motor angles and attach
        # their own parts to it (server.core.protocol.ownership)
        Method("share", (Param("on", "bool", True),), returns="self"),
        KEEP,
    )),
    TypeSpec("EdgedHand", "Robot", (Param("isLeft", "bool", True),), HAND_METHODS),
    TypeSpec("GLTFPart", "Part", (Param("filename", "asset"), Param("length", "number", 0.0)),
             (Method("recolor", (Param("fromColor", "rgb"), Param("toColor", "rgb"),
                                 Param("eps", "number", 0.01))),)),
    TypeSpec("RoundFinger", "GLTFPart", (Param("filename", "asset"),
                                         Param("length", "size", part_figures.ROUND_FINGER_LENGTH)),
             slots=1),
    *(TypeSpec(name, "GLTFPart", (Param("left", "bool"), Param("filename", "asset"),
                                  Param("length", "size", part_figures.ROUND_PALM_LENGTH)), slots=slots)
      for name, slots in (("RoundPalm", 5), ("AnthroPalm", 5), ("AnthroThumb", 1))),
    TypeSpec("SceneMesh", "Part", (Param("geometry", "geometry"),
                               Param("color", "color", part_figures.DEFAULT_COLOR)),
             (Method("setColor", (Param("color", "color"),)),)),
    TypeSpec("RoundHand", "Robot", (Param("isLeft", "bool", True),), HAND_METHODS),
    TypeSpec("AnthroHand", "Robot", (Param("isLeft", "bool", True),), HAND_METHODS),
    # not in the manual: a robot from an uploaded URDF or MJCF (POST /api/scenes/{scene}/robots
    # uploads one; its answer's ``file`` is this argument), and the parts of its links
    TypeSpec("ImportedRobot", "Robot", (Param("file", "robotFile"),)),
    TypeSpec("RobotLink", "Part", creatable=False),
)}


def slot_counts() -> dict[str, int]:
    """The numbered slots each creatable type starts with (sent in ``hello``)."""
    return {spec.name: spec.slots for spec in TYPES.values() if spec.creatable}


def lineage(type_name: str) -> list[TypeSpec]:
    """The type and its bases, most derived first."""
    chain = []
    spec: TypeSpec | None = TYPES[type_name]
    while spec is not None:
        chain.append(spec)
        spec = TYPES[spec.base] if spec.base else None
    return chain


@functools.cache  # the table never changes: a request's lookup is one dict access
def methods_of(type_name: str) -> Mapping[str, Method]:
    """Every method callable on an object of ``type_name``, inherited ones included."""
    found: dict[str, Method] = {}
    for spec in lineage(type_name):
        for method in spec.methods:
            found.setdefault(method.name, method)
    return found
