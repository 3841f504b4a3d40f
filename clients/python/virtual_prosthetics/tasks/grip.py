"""A hand's grip as the tasks use it: its grip map (the server's ``getGripMap``, derived
from its kinematics, or a file's), its motors by index, and where its palm, its grasp and
its tips are when it is turned palm down.

A grip map file (``--grip-map FILE``) is JSON of the schema's ``gripMap`` form with each
motor by ``index`` (its place in ``getMotors()``) or ``name`` (``setName``; an imported
joint's name) instead of its id; ``open`` may be left out (the motor's angle as made)::

    {"digits": [
      {"opposes": true, "motors": [{"name": "thumb_flex", "open": 0, "closed": 1.4}],
       "preshape": [{"index": 0, "closed": -1.0}]},
      {"motors": [{"index": 4, "open": 0, "closed": 1.5}, {"index": 5, "closed": 1.5}]}]}

Its ``digits`` replace the derived ones; the derived frame (centre, approach, forward,
grasp, bounds) stays unless the file gives its own.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np

from ..robots import Robot

FRAME_KEYS = ("centre", "approach", "forward", "grasp", "palmBounds", "handBounds")


@dataclass(frozen=True)
class Closing:
    """A motor (by index) of a digit: its value open and closed."""

    index: int
    open: float
    closed: float

    def at(self, share: float) -> float:
        """``share`` of the way from open (0) to closed (1)."""
        return self.open + (self.closed - self.open) * share


@dataclass(frozen=True)
class GripDigit:
    """A digit: its tip part's id, its closing motors, whether it opposes, its preshape,
    where its tip is open (the robot's frame) and the parts it moves."""

    tip: str | None
    motors: tuple[Closing, ...]
    opposes: bool = False
    preshape: tuple[Closing, ...] = ()
    at: tuple[float, float, float] | None = None
    parts: tuple[str, ...] = ()


@dataclass(frozen=True)
class Layout:
    """The hand turned palm down (``quaternion``: its approach down, forward along -z):
    where its parts are relative to its position, in scene units. ``palm_below`` and
    ``lowest``: how far its palm's underside and its lowest point are below it;
    ``palm_end``: z of the palm's front edge; ``length``: from the palm's back edge to
    the farthest point ahead; ``grasp``: where it holds an object: where its tips meet
    half closed (a gripper's meet under its palm), or under its palm's front edge, amid
    the palm's width, when they meet further ahead (a hand's fingers reach ahead of its
    palm and curl back under it); ``thumb_side``: which way along x the opposing digit lies (0:
    neither)."""

    quaternion: tuple[float, float, float, float]
    centre: tuple[float, float, float]
    grasp: tuple[float, float, float]
    palm_below: float
    lowest: float
    palm_end: float
    length: float
    thumb_side: float


@dataclass(frozen=True)
class HandGrip:
    """A hand's digits and layout, and its motor count (angles are sent all at once)."""

    digits: tuple[GripDigit, ...]
    layout: Layout
    motors: int

    @property
    def opposing(self) -> int:
        """The opposing digit's index (−1: none)."""
        return next((i for i, digit in enumerate(self.digits) if digit.opposes), -1)

    def nearest(self, count: int | None) -> list[int]:
        """The digits a grip of ``count`` closes (None: all): the opposing digit and those
        whose tips lie nearest it (a tip pinch: thumb, index and middle)."""
        if count is None or count >= len(self.digits) or self.opposing < 0:
            return list(range(len(self.digits)))
        thumb = self.digits[self.opposing].at
        def apart(index: int) -> float:
            at = self.digits[index].at
            return 0.0 if index == self.opposing else \
                math.inf if at is None or thumb is None else math.dist(at, thumb)
        return sorted(sorted(range(len(self.digits)), key=apart)[:count])

    def angles(self, shares: Mapping[int, float]) -> list[float | None]:
        """Every motor's angle for ``setAngles``: each digit of ``shares`` (index: share
        closed) closed that far, every preshape applied, the rest left as they are."""
        values: list[float | None] = [None] * self.motors
        for index, digit in enumerate(self.digits):
            for motor in digit.preshape:
                values[motor.index] = motor.closed
            if index in shares:
                for motor in digit.motors:
                    values[motor.index] = motor.at(shares[index])
        return values


def hand_grip(robot: Robot, override: Mapping[str, Any] | None = None) -> HandGrip:
    """``robot``'s grip: its map from the server, ``override``'s digits and frame instead
    where given (a grip map file's, :func:`read_grip_map`)."""
    derived = robot.get_grip_map()
    motors = robot.get_motors()
    found = {**derived, **{key: override[key] for key in FRAME_KEYS if override and key in override}}
    if override is None:
        digits = tuple(_digit(entry, lambda m: m["index"], {}) for entry in derived["digits"])
    else:
        names = {motor.get_name(): i for i, motor in enumerate(motors) if motor.get_name()}
        defaults = {i: motor.get_angle() for i, motor in enumerate(motors)}
        digits = tuple(_digit(entry, lambda m: _index(m, names, len(motors)), defaults)
                       for entry in override["digits"])
    return HandGrip(digits, layout(found), len(motors))


def _digit(entry: Mapping[str, Any], index_of: Any, defaults: Mapping[int, float]) -> GripDigit:
    def closing(item: Mapping[str, Any]) -> Closing:
        index = index_of(item)
        return Closing(index, float(item.get("open", defaults.get(index, 0.0))), float(item["closed"]))
    at = entry.get("tipAt")
    return GripDigit(entry.get("tip"), tuple(closing(m) for m in entry["motors"]),
                     bool(entry.get("opposes", False)),
                     tuple(closing(m) for m in entry.get("preshape", ())),
                     None if at is None else _vec(at), tuple(entry.get("parts", ())))


def _index(item: Mapping[str, Any], names: Mapping[str, int], count: int) -> int:
    """A grip map file's motor: by index, or by name."""
    if "index" in item:
        index = item["index"]
        if not isinstance(index, int) or not 0 <= index < count:
            raise ValueError(f"grip map: motor index {index!r} is not one of the robot's 0-{count - 1}")
        return index
    if item.get("name") not in names:
        raise ValueError(f"grip map: no motor named {item.get('name')!r}; the robot's named motors "
                         f"are {', '.join(sorted(names)) or 'none'}")
    return names[item["name"]]


def read_grip_map(path: str | Path) -> dict[str, Any]:
    """A grip map file, checked to have digits whose motors each say ``closed`` and give
    an ``index`` or a ``name``; ValueError saying what is wrong."""
    try:
        found = json.loads(Path(path).read_text())
    except (OSError, json.JSONDecodeError) as error:
        raise ValueError(f"grip map {path}: {error}") from None
    digits = found.get("digits") if isinstance(found, dict) else None
    if not isinstance(digits, list) or not digits:
        raise ValueError(f"grip map {path}: expected {{\"digits\": [...]}} with at least one digit")
    for number, digit in enumerate(digits):
        for item in (*digit.get("motors", ()), *digit.get("preshape", ())):
            if "closed" not in item or not ("index" in item or "name" in item):
                raise ValueError(f"grip map {path}: digit {number}: each motor needs \"closed\" "
                                 f"and an \"index\" or a \"name\", got {item!r}")
    return found


def layout(found: Mapping[str, Any]) -> Layout:
    """Where a grip map's hand is when turned palm down (see :class:`Layout`)."""
    approach, forward = np.array(found["approach"]), np.array(found["forward"])
    turn = np.array([np.cross(approach, forward), -approach, -forward])  # world = turn @ robot
    centre, grasp = turn @ np.array(found["centre"]), turn @ np.array(found["grasp"])
    palm, hand = found["palmBounds"], found["handBounds"]
    opposing = [d for d in found.get("digits", ()) if d.get("opposes") and "tipAt" in d]
    length = hand["forward"][1] - palm["forward"][0]
    side = float((turn @ np.array(opposing[0]["tipAt"]))[0] - centre[0]) if opposing else 0.0
    if grasp[2] < centre[2] - palm["forward"][1]:  # the tips meet ahead of the palm: a hand
        grasp = np.array([centre[0], grasp[1], centre[2] - palm["forward"][1]])
    return Layout(_quaternion(turn), _vec(centre), _vec(grasp),
                  palm["approach"][1] - centre[1], hand["approach"][1] - centre[1],
                  centre[2] - palm["forward"][1], length,
                  math.copysign(1.0, side) if abs(side) > 0.1 * length else 0.0)


def _quaternion(m: np.ndarray) -> tuple[float, float, float, float]:
    """The quaternion (x, y, z, w) of a rotation matrix (Shepperd's method: numpy has
    none, and the client carries no 3-D library)."""
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace > 0:
        s = 2 * math.sqrt(trace + 1)
        q = ((m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, s / 4)
    else:
        i = int(np.argmax(np.diag(m)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2 * math.sqrt(1 + m[i, i] - m[j, j] - m[k, k])
        v = [0.0, 0.0, 0.0]
        v[i], v[j], v[k] = s / 4, (m[j, i] + m[i, j]) / s, (m[k, i] + m[i, k]) / s
        q = (v[0], v[1], v[2], (m[k, j] - m[j, k]) / s)
    return tuple(float(x) for x in q)  # type: ignore[return-value]


def _vec(v: Sequence[float]) -> tuple[float, float, float]:
    return float(v[0]), float(v[1]), float(v[2])
