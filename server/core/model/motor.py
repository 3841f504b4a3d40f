"""Motors: parts that turn about one axis within limits, or slide along it (:class:`Slider`)."""

from __future__ import annotations

import math
from typing import Any

from ..kit.errors import Cycle, OutOfRange, WrongType
from ..kit import math3d
from ..kit.math3d import Pose, Vec3
from ..kit.numbers import encode_numbers
from ..physics.dynamics import DEFAULT_MAX_FORCE, DEFAULT_MAX_TORQUE
from . import part_figures
from .node import World
from .parts import Part


def clamp(value: float, low: float, high: float) -> float:
    """``value`` limited to [low, high]."""
    return max(low, min(high, value))


class Motor(Part):
    """A part with one rotational degree of freedom; the base motor has no image.

    Its ``axis`` is 'x', 'y' or 'z' (the 1.0 types) or a unit vector (an imported joint's).

    Limits are swapped when given in reverse, the default angle is clamped into them,
    and ``flip`` turns the motor the other way while ``get_angle`` keeps reporting the
    commanded angle.
    """

    type_name = "Motor"
    is_motor = True
    slides = False  # a Slider's value is a length along its axis

    def __init__(self, scene: World, node_id: str, axis: math3d.Axis, min: float = -math.inf,
                 max: float = math.inf, default: float = 0.0) -> None:
        super().__init__(scene, node_id)
        self.axis = axis
        self.min, self.max = (min, max) if min <= max else (max, min)
        if self.min == math.inf or self.max == -math.inf:
            raise OutOfRange(f"the limits of motor {node_id} leave no finite angle: "
                             f"[{self.min}, {self.max}]", object=node_id)
        self.default = clamp(default, self.min, self.max)
        self.angle = self.default
        self.target = self.angle  # dynamic mode: what the motor drives toward (angle: where it is)
        self.max_torque: float | None = None  # N·m in dynamic mode (None: DEFAULT_MAX_TORQUE)
        self.max_speed: float | None = None  # rad/s in dynamic mode (None: no limit)
        self.flipped = False
        self.name: str | None = None
        self.following: tuple[str, float, float] | None = None  # (leader id, ratio, offset)

    def local_pose(self) -> Pose:
        turn = math3d.axis_angle(self.axis, -self.angle if self.flipped else self.angle)
        return self.position, math3d.multiply(self.quaternion, turn)

    def get_angle(self) -> float:
        """Manual ``getAngle()``: in dynamic mode the joint's real angle (a finger stopped by
        an object reads where it stopped)."""
        return self.angle

    @property
    def saved_target(self) -> float | None:
        """``target`` as documents keep it: only where it is not the angle."""
        return None if self.target == self.angle else self.target

    def set_max_torque(self, torque: float) -> Motor:
        """The most torque (N·m) the motor drives with in dynamic mode; returns the motor."""
        self._assign("max_torque", float(torque))
        return self

    def get_max_torque(self) -> float:
        """The motor's torque bound in dynamic mode (N·m)."""
        return DEFAULT_MAX_TORQUE if self.max_torque is None else self.max_torque

    def set_max_speed(self, speed: float) -> Motor:
        """The fastest the motor moves in dynamic mode (rad/s; a slider's: scene units/s), as
        a servo's rated speed: it drives toward its angle no faster (Infinity, the default:
        as fast as its torque allows); returns the motor."""
        self._assign("max_speed", None if math.isinf(speed) else float(speed))
        return self

    def get_max_speed(self) -> float:
        """The motor's speed bound in dynamic mode (Infinity: none)."""
        return math.inf if self.max_speed is None else self.max_speed

    def get_torque(self) -> float:
        """The torque the motor drove with in the last step (N·m; a slider's force, N),
        positive pushing its angle up: the effort a servo's current tells (dynamic mode;
        0 in kinematic mode, where motors jump to their angles)."""
        return self.scene.bodies.motor_motion([self])[0][1]

    def get_speed(self) -> float:
        """How fast the motor turned at the last step (rad/s; a slider's speed), positive
        turning its angle up (dynamic mode; 0 in kinematic mode)."""
        return self.scene.bodies.motor_motion([self])[0][0]

    def set_angle(self, angle: float | None) -> None:
        """Manual ``setAngle(angle)``: None and NaN are ignored, the rest clamped."""
        self.scene.turn([(self, angle)])

    def within_limits(self, angle: float | None) -> float | None:
        """The angle ``setAngle(angle)`` gives this motor (None: it is ignored)."""
        if angle is not None and self.min <= angle <= self.max and math.isfinite(angle):
            return angle  # the common case, in one test (NaN fails it too)
        if angle is None or math.isnan(angle):
            return None
        value = clamp(angle, self.min, self.max)
        if not math.isfinite(value):
            raise OutOfRange(f"angle {angle} of motor {self.id} is not finite within its "
                             f"limits [{self.min}, {self.max}]", object=self.id)
        return value

    def get_name(self) -> str | None:
        """The name ``setName`` gave it (an imported joint's: the file's), or None."""
        return self.name

    def set_name(self, name: str) -> Motor:
        """Manual ``setName(name)``; returns the motor for chaining."""
        self._assign("name", name)
        return self

    def flip(self, flipped: bool = True) -> Motor:
        """Manual ``flip(bool)``: turn the other way when true; returns the motor."""
        self._assign("flipped", flipped)
        return self

    def follow(self, leader: Motor | None = None, ratio: float = 1.0, offset: float = 0.0) -> Motor:
        """Turn with ``leader`` from now on: whenever the leader is set to ``a``, this motor
        is set to ``ratio·a + offset`` (within its own limits) in the same tick, as one
        joint of a linkage or tendon (URDF ``<mimic>``, MJCF ``<equality><joint>``). A
        follower's own ``setAngle`` is ignored while it follows; ``follow()`` frees it.
        Returns the motor."""
        if leader is None:
            self._assign("following", None)
            return self
        if not isinstance(leader, Motor):
            raise WrongType(f"{self.id} can only follow a motor; {leader.id} is a "
                            f"{leader.type_name}", object=self.id)
        step: Motor | None = leader
        while step is not None:
            if step is self:
                raise Cycle(f"{self.id} cannot follow {leader.id}: {leader.id} turns with "
                            f"{self.id} already", object=self.id, leader=leader.id)
            step = step.leader()
        self._assign("following", (leader.id, float(ratio), float(offset)))
        self.set_angle_following(leader)
        return self

    def leader(self) -> Motor | None:
        """The motor this one follows, if it is still in the scene."""
        if self.following is None:
            return None
        node = self.scene.nodes.get(self.following[0])
        return node if isinstance(node, Motor) else None

    def set_angle_following(self, leader: Motor) -> None:
        """Where a new follower goes at once: its share of the leader's angle."""
        self.scene.turn([(self, self.share_of(leader.target))], coupled=False)

    def share_of(self, leader_angle: float) -> float | None:
        """A follower's angle when its leader is at ``leader_angle``: ``ratio·a + offset``
        within its own limits (None: not a follower, or no finite angle)."""
        if self.following is None:
            return None
        _, ratio, offset = self.following
        return self.within_limits(ratio * leader_angle + offset)

    def constructor_args(self) -> list[Any]:
        return [self.axis, self.min, self.max, self.default]

    def properties(self) -> dict[str, Any]:
        return {**super().properties(), "axis": self.axis, "min": self.min, "max": self.max,
                "angle": self.angle, "flipped": self.flipped, "name": self.name,
                "maxTorque": self.get_max_torque(), "maxSpeed": encode_numbers(self.get_max_speed()),
                "follows": None if self.following is None else list(self.following)}


class AxisMotor(Motor):
    """A motor class with a fixed axis, drawn as a cylinder, with slot 0 per the part_figures."""

    def __init__(self, scene: World, node_id: str, min: float = -math.inf,
                 max: float = math.inf, default: float = 0.0, width: float | None = None,
                 height: float | None = None) -> None:
        figure = part_figures.MOTORS[self.type_name]
        super().__init__(scene, node_id, figure.axis, min, max, default)
        self.width = figure.width if width is None else width
        self.height = figure.height if height is None else height
        self.new_slot(part_figures.motor_slot(figure.axis, self.height))

    def constructor_args(self) -> list[Any]:
        return [self.min, self.max, self.default, self.width, self.height]

    def geometry(self) -> dict[str, Any]:
        return part_figures.motor_cylinder(self.type_name, self.width, self.height)


class MotorX(AxisMotor):
    type_name = "MotorX"


class MotorY(AxisMotor):
    type_name = "MotorY"


class MotorZ(AxisMotor):
    type_name = "MotorZ"


class Slider(Motor):
    """A motor that moves what hangs on it along its axis instead of turning it: a linear
    actuator, or an imported prismatic (URDF) or slide (MJCF) joint.

    Its value (``getAngle``/``setAngle``, the names the 1.0 API gives a motor's value) and
    its limits are lengths in scene units, measured in the scene whatever the scales above
    it; its bound in dynamic mode is a force in newtons (``setMaxTorque`` sets it).
    """

    type_name = "Slider"
    slides = True

    def local_pose(self) -> Pose:
        direction = math3d.rotate(self.quaternion, math3d.unit_axis(self.axis))
        along = (-self.angle if self.flipped else self.angle) / self._stretch(direction)
        return tuple(p + d * along for p, d in zip(self.position, direction)), self.quaternion  # type: ignore[return-value]

    def _stretch(self, direction: Vec3) -> float:
        """How much the scales above stretch a length along ``direction`` (a parent's scale
        stretches where its children sit)."""
        if self.parent is None:
            return 1.0
        return math.hypot(*(d * s for d, s in zip(direction, self.parent.world_scale()))) or 1.0

    def get_max_torque(self) -> float:
        """The slider's force bound in dynamic mode (N)."""
        return DEFAULT_MAX_FORCE if self.max_torque is None else self.max_torque

    def properties(self) -> dict[str, Any]:
        return {**super().properties(), "slides": True}
