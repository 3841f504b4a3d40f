"""A scene's physics settings: kinematic or dynamic, and the dynamic options checked
(:class:`Physics`), with the units Bullet takes them in (:class:`BulletUnits`).

A scene is kinematic (1.0's behaviour: motors jump to their angles, nothing falls, contacts
are reported, not resolved) or dynamic (:mod:`.dynamics`).

Defaults, and why (:class:`Physics`):

- ``unit`` DEFAULT_UNIT metres per scene unit: positions, sizes and the 1.0 API stay in
  scene units (1.0's figures), and everything else is SI at the size the unit makes
  things: gravity (m/s²), masses (kg), densities (kg/m³), torques (N·m) and forces (N).
  By default a 1.0 hand is a human hand's size (palm to tip 0.19 m); a robot imported
  from a file in metres keeps its size beside it. Bullet itself works in scene units of
  length and masses of unit³ kg (:class:`BulletUnits`: a density in kg/m³ is the same
  number in it), so a 1.0 hand's figures in Bullet are near what they were before units
  and one conversion at Bullet's door keeps the solver's figures as they were tuned.
- ``gravity`` 9.81 m/s² down (−Y).
- ``substeps`` 5: physics steps of 1/300 s (five per 60 Hz tick). PyBullet's grasping
  examples step at 240 Hz or more; fewer steps let fingers sink into what they squeeze.
- ``solverIterations`` 50: the fewest of the 50-150 that PyBullet's examples use with
  which a closed hand holds its objects (more cost time every step).
- ``solverTolerance`` 0.05: the solver ends a step's iterations early once one changes no
  constraint row's velocity by more than this share of the speed gravity gives anything in
  a step (Bullet's residual threshold: Bullet measures a row's change as a velocity, so a
  share of an impulse, as this was first, let fingers of grams sag 0.07 rad at a human
  unit while ones of a 1.0 hand's Bullet masses held). Free bodies alone settle in a few
  iterations instead of all of them (an animated hand's motors do not: it used every
  iteration in 86 % of its steps); held objects hold as with every iteration (the grasp
  task's table), and a heavy hand under strong gravity stays within 1 mm of its mount; 0
  runs every iteration of every step.
- ``warmStart`` 0 (off): a contact's solve begins each step from this share of its
  impulse of the step before, not from nothing (:mod:`.warm_start`: Bullet's articulated
  warm starting, which PyBullet builds but does not offer; Bullet's own figure is 0.85).
  At the same iterations a tower of boxes sinks about half as far. The grasping tasks
  run warm at 60 iterations (their table measured again: about as many grasps hold as
  cold at 150, in 70 % of the CPU), Box and Blocks at 30. Off by default: it changes
  which grasps hold, and a script's world stays as it was tuned (warm at 25 or 30 a heavy
  ball dropped on a heap sank into it, and a ball squeezed in a lifted hand crept 5 mm in
  2 s at 30, 100 and 150 iterations, where every cold count from 50 held it).
- ``friction`` 1.0 (lateral): rubber-like fingers on hard objects, PyBullet's examples'
  value; spinning friction is a tenth of it and rolling friction a thousandth, so a held
  ball neither spins nor rolls out. Every body has Bullet's friction anchors: without them
  a contact that sticks still creeps a little every step, and a squeezed ball crept out
  of a closed hand by millimetres a second.
- ``density`` 1240 kg/m³ (PLA, what printed prosthetic hands are made of): a part's mass
  is its volume times this, unless ``setMass`` gave it one. A 1.0 hand then weighs
  0.22-0.27 kg at the default unit (0.17-0.22 kg of water: its parts are 1.6 cm thick).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from typing import Any

from ..kit.errors import BadArguments, OutOfRange, WrongType, show

KINEMATIC, DYNAMIC = "kinematic", "dynamic"
MODES = (KINEMATIC, DYNAMIC)
NOMINAL_TICK = 1 / 60  # substeps are counted per this much time

# The 1.0 edged hand's palm to tip (3.5 scene units) as a human's (0.19 m, wrist crease to
# the middle finger's tip): 1.0 hands at a human hand's size.
DEFAULT_UNIT = 0.19 / 3.5

_RANGES: dict[str, tuple[float, float, type]] = {
    "unit": (1e-4, 100.0, float), "gravity": (-1000.0, 1000.0, float), "substeps": (1, 20, int),
    "solverIterations": (1, 500, int), "solverTolerance": (0.0, 1.0, float),
    "friction": (0.0, 10.0, float),
    "density": (1.0, 100_000.0, float), "warmStart": (0.0, 1.0, float),
}


@dataclass(frozen=True)
class Physics:
    """A scene's physics: its mode and, for dynamic mode, its options (wire names)."""

    mode: str = KINEMATIC
    unit: float = DEFAULT_UNIT
    gravity: float = 9.81
    substeps: int = 5
    solverIterations: int = 50  # noqa: N815 (the wire's name)
    solverTolerance: float = 0.05  # noqa: N815
    friction: float = 1.0
    density: float = 1240.0
    warmStart: float = 0.0  # noqa: N815

    @property
    def dynamic(self) -> bool:
        return self.mode == DYNAMIC

    @property
    def step(self) -> float:
        """Seconds of one physics step."""
        return NOMINAL_TICK / self.substeps

    def wire(self) -> dict[str, Any]:
        """As ``getPhysics`` answers and documents keep it."""
        return asdict(self)

    @property
    def bullet(self) -> BulletUnits:
        """How this scene's SI figures go into Bullet and come out."""
        return BulletUnits(self.unit)

    @classmethod
    def of(cls, mode: Any, options: Any = None) -> Physics:
        """From ``setPhysics(mode, options)``: options left out take their defaults."""
        if mode not in MODES:
            raise OutOfRange(f"physics mode must be kinematic or dynamic, got {show(mode)}",
                             mode=show(mode))
        if options is None:
            options = {}
        if not isinstance(options, dict):
            raise WrongType(f"physics options: expected an object like {{\"gravity\": 9.81}}, "
                            f"got {show(options)}")
        unknown = set(options) - set(_RANGES)
        if unknown:
            raise BadArguments(f"physics options: no option {', '.join(sorted(unknown))}; the "
                               f"options are {', '.join(_RANGES)}")
        return replace(cls(mode), **{name: _option(name, value) for name, value in options.items()})


@dataclass(frozen=True)
class BulletUnits:
    """Bullet's units in a scene of ``unit`` metres per scene unit: lengths in scene units,
    seconds, and masses in the mass of a scene unit's cube of water over 1000 (so a
    density in kg/m³ is the same number in Bullet's units); forces and torques follow."""

    unit: float

    @property
    def mass(self) -> float:
        """Kilograms in one Bullet unit of mass."""
        return self.unit ** 3

    @property
    def force(self) -> float:
        """Newtons in one Bullet unit of force (mass × length / s²)."""
        return self.unit ** 4

    @property
    def torque(self) -> float:
        """N·m in one Bullet unit of torque (and kg·m² in one of inertia)."""
        return self.unit ** 5

    def acceleration(self, metres_per_s2: float) -> float:
        return metres_per_s2 / self.unit


def _option(name: str, value: Any) -> float | int:
    low, high, kind = _RANGES[name]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or \
            (kind is int and value != int(value)) or not math.isfinite(value):
        raise WrongType(f"physics option {name}: expected {'a whole' if kind is int else 'a'} "
                        f"number, got {show(value)}", option=name)
    if not low <= value <= high:
        raise OutOfRange(f"physics option {name} must be within [{low}, {high}], got {value}",
                         option=name)
    return kind(value)
