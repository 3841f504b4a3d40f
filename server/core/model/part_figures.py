"""The figures of the 1.0 parts: defaults, profiles, slots and hand chains.

Every number that `spec/parts.md` gives for a part lives here and nowhere else; the part
classes, the API table and the viewer's geometry all read them from this module.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..kit.math3d import Vec3

PI = math.pi

DEFAULT_COLOR = "dimgray"
MOTOR_COLOR = "#404040"
EDGE_EPSILON = 0.003  # E in the spec: keeps the flat ends of edged fingers off the slot plane


@dataclass(frozen=True)
class MotorFigure:
    """Drawing and slot rules of one motor class."""

    axis: str
    width: float
    height: float
    sides: int


MOTORS: dict[str, MotorFigure] = {
    "MotorX": MotorFigure("x", 0.1, 0.05, 16),
    "MotorY": MotorFigure("y", 0.3, 0.05, 48),  # the manual says 0.1; 1.0 uses 0.3
    "MotorZ": MotorFigure("z", 0.1, 0.05, 16),
}


def motor_slot(axis: str, height: float) -> Vec3:
    """Slot 0 of a motor: its centre, or its top for the Y motor."""
    return (0.0, height, 0.0) if axis == "y" else (0.0, 0.0, 0.0)


def motor_cylinder(motor_type: str, width: float, height: float) -> dict:
    """The cylinder a motor is drawn as, in the motor's own frame."""
    figure = MOTORS[motor_type]
    if figure.axis == "y":
        radius, length, center = width / 2, height, [0.0, height / 2, 0.0]
    else:
        radius, length, center = height / 2, width, [0.0, 0.0, 0.0]
    return {"kind": "cylinder", "axis": figure.axis, "radius": radius, "length": length,
            "center": center, "sides": figure.sides, "color": MOTOR_COLOR}


# --- edged parts ---------------------------------------------------------------------

EDGED_FINGER_DEFAULTS = {"length": 1.0, "width": 0.3, "thickness": 0.3}
EDGED_PALM_DEFAULTS = {"length": 1.4, "width": 1.4, "thickness": 0.3}


def edged_finger_profile(length: float, thickness: float, tip: bool) -> list[tuple[float, float]]:
    """The XY profile of an edged finger (or tip), extruded along Z into the part."""
    big_l, t, e = length, thickness / 2, EDGE_EPSILON
    i = min(length, thickness) / 8
    top = [(t, big_l - i - e), (t - i, big_l - e)] if tip else [(t, big_l - t - e), (0.0, big_l - e)]
    return [(-t, i), (-t + i, e), (0.0, e), (t, t), *top, (-t + i, big_l - e), (-t, big_l - i)]


def edged_palm_profile(left: bool, length: float, width: float) -> list[tuple[float, float]]:
    """Points p0…p5 of the edged palm profile, extruded along Z into the palm."""
    s = 1.0 if left else -1.0
    w, i, big_l = width / 2, width / 8, length
    return [(-s * w + s * i, 0.0), (s * w - 2 * s * i, 0.0), (s * w, 2 * i),
            (s * w, big_l), (-s * w, big_l), (-s * w, big_l / 2)]


def extrude(profile: list[tuple[float, float]], depth: float) -> list[Vec3]:
    """Points of a profile at z = -depth/2 and z = +depth/2 (the convex envelope's points)."""
    half = depth / 2
    return [(x, y, z) for z in (-half, half) for (x, y) in profile]


# Edges of the palm profile that carry slots: (from point, to point, fraction) per slot.
EDGED_PALM_SLOTS = [(2, 3, 1 / 4), (3, 4, 1 / 8), (3, 4, 3 / 8), (3, 4, 5 / 8), (3, 4, 7 / 8)]


def edged_palm_slots(left: bool, length: float, width: float) -> list[tuple[Vec3, Vec3, str]]:
    """Position, Euler rotation and order of the five edged palm slots (thumb first)."""
    s = 1.0 if left else -1.0
    points = edged_palm_profile(left, length, width)
    slots = []
    for a, b, k in EDGED_PALM_SLOTS:
        (xa, ya), (xb, yb) = points[a], points[b]
        position = (xa * (1 - k) + xb * k, ya * (1 - k) + yb * k, 0.0)
        rotation = (0.0, PI / 2, (1 + s) * PI / 2 + math.atan2(yb - ya, xb - xa))
        slots.append((position, rotation, "ZXY"))
    return slots


# --- round and anthropomorphic parts (meshes) ----------------------------------------

# Bounding boxes ((x0, x1), (y0, y1), (z0, z1)) of the bundled meshes in their files' own
# frames: 1.0's proportions (generate/meshes.py makes the files to fit them).
MESH_BOUNDS: dict[str, tuple[tuple[float, float], ...]] = {
    "round-finger-8.glb": ((-0.15, 0.15), (-0.456, 0.474), (-0.15, 0.15)),
    "round-finger-5.glb": ((-0.15, 0.15), (-0.312, 0.324), (-0.15, 0.15)),
    "round-tip.glb": ((-0.15, 0.15), (-0.312, 0.324), (-0.15, 0.15)),
    "round-palm.glb": ((-0.825, 0.821), (-0.864, 1.03), (-0.15, 0.15)),
    "anthro-palm.glb": ((-0.805, 0.76), (-0.864, 1.03), (-0.15, 0.15)),
    "anthro-thumb.glb": ((-0.114, 0.116), (-0.33, 0.112), (-0.256, 0.292)),
}
MESH_WHITE = (1.0, 1.0, 1.0)  # flat faces
MESH_BLUE = (0.0, 0.21, 1.0)  # curved faces
ROUND_HAND_GREY = (0.3, 0.3, 0.3)  # what a round hand recolours the blue to
ROUND_FINGER_LENGTH = 0.8
ROUND_PALM_LENGTH = 1.4

SlotFigure = tuple[Vec3, Vec3, str]  # position, Euler rotation, order
# Envelopes of mesh parts stop short of their joints (server.core.physics.envelopes): a finger's
# ends are pyramids beginning FINGER_JOINT_GAP beyond its joints; a palm keeps
# PALM_JOINT_GAP behind its finger slots and inside a round hand's thumb slot.
FINGER_JOINT_GAP = 0.01
PALM_JOINT_GAP = 0.02


def _finger_slots(f: float, length: float) -> list[SlotFigure]:
    """Slots 1-4 of round and anthropomorphic palms (index to little finger)."""
    spots = [(0.36, 1.13, -3), (0.12, 1.17, -1), (-0.12, 1.16, 1), (-0.36, 1.09, 3)]
    return [((x * f * length, y * length, 0.0), (0.0, PI / 2, k * f * PI / 180), "ZXY")
            for x, y, k in spots]


def round_palm_slots(left: bool, length: float) -> list[SlotFigure]:
    """The five slots of a round palm, the thumb's first."""
    f = 1.0 if left else -1.0
    thumb = ((0.53 * f * length, 0.50 * length, 0.0),
             (PI / 2 * (1 + f), -f * PI / 2, PI / 2 + 0.7 * f), "ZXY")
    return [thumb, *_finger_slots(f, length)]


def anthro_palm_slots(left: bool, length: float) -> list[SlotFigure]:
    """The five slots of an anthropomorphic palm, the thumb's first."""
    f = 1.0 if left else -1.0
    thumb = ((0.32 * f * length, 0.16 * length, 0.0),
             (PI / 2, 0.75 * PI + (0.0 if left else PI / 2), -0.5 * f * PI), "XYZ")
    return [thumb, *_finger_slots(f, length)]


def anthro_thumb_slot(left: bool, length: float) -> SlotFigure:
    """The one slot of an anthropomorphic thumb, where its finger goes on."""
    f = 1.0 if left else -1.0
    return (0.0, -0.2 * length, 0.06 * length), (PI / 2, (1 - f) * PI / 2, 0.0), "XYZ"

# --- sensors --------------------------------------------------------------------------

SENSOR_PAD_RADIUS = 0.1   # the dome's radius in X and Z
SENSOR_PAD_HEIGHT = 0.05  # and along +Y, the sensing direction
SENSOR_PAD_COLOR = "lightgray"
SENSOR_NEAR = 0.05        # senseDistance ignores hits nearer than the pad's size
TOUCH_RANGE = 0.05        # senseTouch sees hits in [0, TOUCH_RANGE]
SENSOR_RANGE = 10_000.0   # a ray must end somewhere: farther than this reads Infinity
LASER_COLOR = "crimson"   # Sensor(visible, true)


def sensor_pad() -> dict:
    """The pad a visible sensor is drawn as: a half dome over its +Y axis."""
    return {"kind": "dome", "radius": SENSOR_PAD_RADIUS, "height": SENSOR_PAD_HEIGHT,
            "color": SENSOR_PAD_COLOR}


# --- hands ----------------------------------------------------------------------------

FINGER_NAMES = ["Thumb", "Index finger", "Middle finger", "Ring finger", "Little finger"]
EDGED_FINGER_SIZES = [1.0, 1.0, 1.1, 1.0, 0.8]
EDGED_FLEX_MOTOR = (0.0, -PI / 2, -PI / 4, 0.3, 0.1)  # MotorZ(min, max, def, width, height)


def edged_spread_motor(finger: int) -> tuple[float, float, float, float, float]:
    """MotorX arguments of the spread motor at the base of an edged finger."""
    span = 1.0 if finger == 0 else 0.4
    return (-span, span, 0.0, 0.3, 0.1)


# spreadFingers(a): the thumb's angle (when included) is offset + scale * a, the other
# four fingers' angles are share * a.
SPREAD_THUMB = {"EdgedHand": (-1.0, 3.0), "RoundHand": (0.0, -3.0), "AnthroHand": (0.5, -2.0)}
SPREAD_FINGERS = (1.0, 0.3, -0.3, -1.0)

# Round hand: (motor type, min, max, def, width, height, flip when left) of each spread
# motor, then the three flexing motors and fingers of every finger.
ROUND_THUMB_SPREAD = ("MotorY", 0.0, PI / 2, 0.0, 0.25, 0.1, False)
ROUND_FINGER_SPREAD = ("MotorX", -0.4, 0.4, 0.0, 0.0, 0.0, True)
ROUND_FLEX = [("proximal", (PI / 4, -PI / 2, -PI / 4, 0.2, 0.07), "round-finger-8.glb", 0.8),
              ("middle", (0.0, -PI / 2, -PI / 4, 0.2, 0.07), "round-finger-5.glb", 0.5),
              ("distal", (0.0, -PI / 2, -PI / 4, 0.2, 0.07), "round-tip.glb", 0.5)]
# Anthropomorphic hand: the thumb's four motors (type, name, min, max, def, width, height,
# flip when left) around its AnthroThumb, and the fingers' flexing motors.
ANTHRO_THUMB_MOTORS = [("MotorZ", "Palm", 0.0, 2.0, 0.0, 0.75, 0.07, False),
                       ("MotorX", "Thumb", -0.75, 2.0, 0.0, 0.14, 0.06, False),
                       ("MotorY", "twist", -0.5, 1.0, 0.0, 0.07, 0.2, False),
                       ("MotorZ", "proximal", -1.75, 0.25, 0.0, 0.2, 0.06, None)]
ANTHRO_PROXIMAL = (PI / 4, -PI / 2, -PI / 8, 0.2, 0.07)
ANTHRO_FLEX = (0.0, -PI / 2, -PI / 8, 0.2, 0.07)

# --- scene ----------------------------------------------------------------------------

CAMERA_POSITION: Vec3 = (4.0, 4.0, 7.0)
CAMERA_TARGET: Vec3 = (0.0, 1.0, 0.0)
