"""Checking wire arguments against the API table and turning them into Python values.

Non-finite numbers travel as the strings ``"Infinity"``, ``"-Infinity"`` and ``"NaN"``
(JSON has no such numbers); ``null`` stands for a left-out argument (JavaScript's
``undefined``), except for an ``angle``, where it means "leave the motor as it is".
"""

from __future__ import annotations

import math
import re
from typing import Any, Callable, Sequence

from ..kit.errors import BadArguments, OutOfRange, WrongType, show
from ..kit.limits import MAX_COORDINATE, MAX_SIZE, MIN_SIZE
from ..kit.math3d import EULER_ORDERS, Quat, Vec3
from ..kit.numbers import NON_FINITE
from ..model.motor import Motor
from ..model.node import Node, Slot
from ..model.parts import Part
from ..model.robot import Robot
from ..physics.bullet_parts import GROUND
from ..physics.settings import MODES
from ..scene.clock import MAX_STEP_TICKS
from .api import REQUIRED, Param

Resolver = Callable[[str], Node]

MAX_STRING = 200
_COLOR = re.compile(r"#[0-9a-fA-F]{3,8}|[a-zA-Z]{3,40}")


def bind(params: Sequence[Param], raw: Sequence[Any], resolve: Resolver, where: str) -> list[Any]:
    """The Python arguments for ``params`` from the wire arguments ``raw``."""
    values: list[Any] = []
    position = 0
    for param in params:
        if param.variadic:
            items = raw[position:]
            if param.kind in _PLAIN_NUMBERS and all(type(v) is float for v in items) and \
                    all(map(math.isfinite, items)):
                values.extend(items)  # setAngles' angles, as they came
            else:
                values.extend(_coerce(param, item, resolve, f"{where}, argument {position + i}")
                              for i, item in enumerate(items))
            return values
        if param.kind == "point":
            value, used = _point(param, raw, position, where)
        else:
            value, used = _single(param, raw, position, resolve, where)
        values.append(value)
        position += used
    if position < len(raw):
        raise BadArguments(f"{where} takes at most {position} arguments, got {len(raw)}",
                           expected=position, got=len(raw))
    return values


def _single(param: Param, raw: Sequence[Any], position: int, resolve: Resolver,
            where: str) -> tuple[Any, int]:
    present = position < len(raw)
    value = raw[position] if present else None
    kind = type(value)
    if (kind is float and param.kind in _PLAIN_NUMBERS and math.isfinite(value)) or \
            (kind is bool and param.kind == "bool"):
        return value, 1  # as _coerce gives it, without the label an error would need
    if value is None and not (present and param.kind == "angle"):
        if param.default is REQUIRED:
            raise BadArguments(f"{where} needs argument {position} ({param.name})",
                               argument=position, name=param.name)
        return param.default, 1 if present else 0
    return _coerce(param, value, resolve, f"{where}, argument {position} ({param.name})"), 1


def _point(param: Param, raw: Sequence[Any], position: int, where: str) -> tuple[Any, int]:
    """A point given as [x, y, z] (one argument) or as x, y, z (three), or left out."""
    value = raw[position] if position < len(raw) else None
    label = f"{where}, argument {position} ({param.name})"
    if value is None:
        if param.default is REQUIRED:
            raise BadArguments(f"{where} needs a {param.name} ([x, y, z] or x, y, z)",
                               argument=position, name=param.name)
        return param.default, 1 if position < len(raw) else 0
    if isinstance(value, list):
        return _vector(value, label), 1
    return _vector(list(raw[position:position + 3]), label), 3


def _vector(items: list[Any], label: str) -> Vec3:
    if len(items) != 3:
        raise BadArguments(f"{label}: a point needs 3 numbers, got {len(items)}")
    point = tuple(_number(item, label) for item in items)
    if any(abs(c) > MAX_COORDINATE for c in point):
        raise OutOfRange(f"{label}: coordinates lie within ±{MAX_COORDINATE:g} m, got "
                         f"{', '.join(show(c) for c in point)}")
    return point  # type: ignore[return-value]


def _number(value: Any, label: str, allow: tuple[str, ...] = ()) -> float:
    if isinstance(value, str) and value in allow:
        return NON_FINITE[value]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise WrongType(f"{label}: expected a number, got {show(value)}")
    if isinstance(value, int) and abs(value) > 2 ** 53:
        raise OutOfRange(f"{label}: {show(value)} is too large")
    if not math.isfinite(value):
        raise OutOfRange(f"{label}: {value} is not a finite number")
    return float(value)


def _quaternion(value: Any, resolve: Resolver, label: str) -> Quat:
    """[x, y, z, w], any length but zero: made a unit quaternion."""
    if not isinstance(value, list) or len(value) != 4:
        raise WrongType(f"{label}: expected a quaternion [x, y, z, w], got {show(value)}")
    q = [_number(item, label) for item in value]
    norm = math.sqrt(sum(c * c for c in q))
    if norm < 1e-9 or norm > 1e9:
        raise OutOfRange(f"{label}: a quaternion needs a length between 1e-9 and 1e9, got {norm:g}")
    if abs(norm - 1.0) < 1e-12:
        return tuple(q)  # type: ignore[return-value]  # a unit one stays bit for bit (restored ones)
    return tuple(c / norm for c in q)  # type: ignore[return-value]


def _axis(value: Any, resolve: Resolver, label: str) -> str | Vec3:
    """'x', 'y', 'z', or [x, y, z] of any length but zero: made a unit vector."""
    if isinstance(value, list):
        if len(value) != 3:
            raise WrongType(f"{label}: expected an axis 'x', 'y', 'z' or [x, y, z], got {show(value)}")
        v = [_number(item, label) for item in value]
        norm = math.sqrt(sum(c * c for c in v))
        if norm < 1e-9 or norm > 1e9:
            raise OutOfRange(f"{label}: an axis needs a length between 1e-9 and 1e9, got {norm:g}")
        return tuple(v) if abs(norm - 1.0) < 1e-12 else tuple(c / norm for c in v)  # type: ignore[return-value]
    if value not in ("x", "y", "z"):
        raise OutOfRange(f"{label}: expected an axis 'x', 'y', 'z' or [x, y, z], got {show(value)}")
    return value


def _scale(value: Any, resolve: Resolver, label: str) -> Vec3:
    """[x, y, z], each from 0 to MAX_SIZE (three.js allows more; a shape needs no more)."""
    if not isinstance(value, list) or len(value) != 3:
        raise WrongType(f"{label}: expected a scale [x, y, z], got {show(value)}")
    scale = tuple(_number(item, label) for item in value)
    if not all(0 <= s <= MAX_SIZE for s in scale):
        raise OutOfRange(f"{label}: each scale lies between 0 and {MAX_SIZE:g}, got "
                         f"{', '.join(show(s) for s in scale)}")
    return scale  # type: ignore[return-value]


def _geometry(value: Any, resolve: Resolver, label: str) -> dict[str, Any]:
    if not isinstance(value, dict):  # the SceneMesh checks the rest against the scene's limits
        raise WrongType(f"{label}: expected a geometry {{\"kind\": …}}, got {show(value)}")
    return value


Transform = tuple[Node, Vec3, Quat, "Vec3 | None"]  # node, position, rotation, scale


def _transforms(value: Any, resolve: Resolver, label: str) -> list[Transform]:
    """{id: [px, py, pz, qx, qy, qz, qw] or the same and sx, sy, sz}, every id resolved."""
    if not isinstance(value, dict):
        raise WrongType(f"{label}: expected {{id: [px, py, pz, qx, qy, qz, qw(, sx, sy, sz)]}}, "
                        f"got {show(value)}")
    out = []
    for object_id, numbers in value.items():
        where = f"{label}, {object_id}"
        if not isinstance(numbers, list) or len(numbers) not in (7, 10):
            raise WrongType(f"{where}: expected 7 or 10 numbers, got {show(numbers)}")
        node = resolve(object_id)
        scale = _scale(numbers[7:], resolve, where) if len(numbers) == 10 else None
        out.append((node, _vector(numbers[:3], where), _quaternion(numbers[3:7], resolve, where),
                    scale))
    return out


def _coerce(param: Param, value: Any, resolve: Resolver, label: str) -> Any:
    return _KINDS[param.kind](value, resolve, label)


# Kinds that take any finite float as it is: a variadic list of such floats (setAngles'
# 20 angles) skips the general path, whose per-item label alone was a fifth of a request.
_PLAIN_NUMBERS = frozenset({"number", "limit", "angle"})


def _size(value: Any, resolve: Resolver, label: str) -> float:
    number = _number(value, label)
    if not MIN_SIZE <= number <= MAX_SIZE:
        raise OutOfRange(f"{label}: a size lies between {MIN_SIZE:g} and {MAX_SIZE:g} m, "
                         f"got {number:g}")
    return number


def _integer(value: Any, resolve: Resolver, label: str) -> int:
    number = _number(value, label)
    if number != int(number):
        raise WrongType(f"{label}: expected a whole number, got {number}")
    return int(number)


def _ticks(value: Any, resolve: Resolver, label: str) -> int:
    ticks = _integer(value, resolve, label)
    if not 1 <= ticks <= MAX_STEP_TICKS:
        raise OutOfRange(f"{label}: a step is 1 to {MAX_STEP_TICKS} ticks, got {ticks}")
    return ticks


def _bool(value: Any, resolve: Resolver, label: str) -> bool:
    if not isinstance(value, bool):
        raise WrongType(f"{label}: expected true or false, got {show(value)}")
    return value


def _string(value: Any, resolve: Resolver, label: str) -> str:
    if not isinstance(value, str):
        raise WrongType(f"{label}: expected a string, got {show(value)}")
    if len(value) > MAX_STRING:
        raise OutOfRange(f"{label}: at most {MAX_STRING} characters, got {len(value)}")
    return value


def _color(value: Any, resolve: Resolver, label: str) -> str | int:
    if isinstance(value, int) and not isinstance(value, bool) and 0 <= value <= 0xFFFFFF:
        return value
    if isinstance(value, str) and _COLOR.fullmatch(value):
        return value
    raise WrongType(f"{label}: expected a CSS colour name, #hex or 0xRRGGBB, got {show(value)}")


def _rgb(value: Any, resolve: Resolver, label: str) -> str | int | list[float]:
    if isinstance(value, list):
        if len(value) == 3 and all(isinstance(c, (int, float)) and not isinstance(c, bool)
                                   and 0 <= c <= 1 for c in value):
            return [float(c) for c in value]
        raise WrongType(f"{label}: expected [r, g, b] with each in 0…1, got {show(value)}")
    return _color(value, resolve, label)


def _choice(options: Sequence[str]) -> Callable[[Any, Resolver, str], str]:
    def check(value: Any, resolve: Resolver, label: str) -> str:
        if value not in options:
            raise OutOfRange(f"{label}: expected one of {', '.join(options)}, got {show(value)}")
        return value
    return check


def _reference(*types: type[Node]) -> Callable[[Any, Resolver, str], Node]:
    names = " or ".join(t.__name__.lower() for t in types)

    def check(value: Any, resolve: Resolver, label: str) -> Node:
        if not (isinstance(value, dict) and set(value) == {"ref"} and isinstance(value["ref"], str)):
            raise WrongType(f"{label}: expected a {names} reference {{\"ref\": id}}, "
                            f"got {show(value)}")
        node = resolve(value["ref"])
        if not isinstance(node, types):
            raise WrongType(f"{label}: {node.id} is a {node.type_name}, not a {names}")
        return node
    return check


def _laser(value: Any, resolve: Resolver, label: str) -> str | int | bool:
    return value if isinstance(value, bool) else _color(value, resolve, label)


def _contact(value: Any, resolve: Resolver, label: str) -> Node | str:
    if value == GROUND:
        return GROUND
    return _reference(Part)(value, resolve, label)


def _slot(value: Any, resolve: Resolver, label: str) -> int | Node:
    if isinstance(value, dict):
        return _reference(Slot)(value, resolve, label)
    index = _integer(value, resolve, label)
    if index < 0:
        raise OutOfRange(f"{label}: a slot index cannot be negative, got {index}")
    return index


def _ranged(low: float, high: float, what: str, low_open: bool = False) -> Callable[[Any, Resolver, str], float]:
    """A number within [low, high] (``low_open``: above low)."""
    def check(value: Any, resolve: Resolver, label: str) -> float:
        number = _number(value, label)
        if not (low < number if low_open else low <= number) or number > high:
            raise OutOfRange(f"{label}: {what} lies {'above' if low_open else 'between'} "
                             f"{low:g}{'' if low_open else ' and ' + format(high, 'g')}"
                             f"{', at most ' + format(high, 'g') if low_open else ''}, got {number:g}")
        return number
    return check


def _speed(value: Any, resolve: Resolver, label: str) -> float:
    number = _number(value, label, ("Infinity",))
    if not number > 0:
        raise OutOfRange(f"{label}: a speed lies above 0 (Infinity: no limit), got {number:g}")
    return number


def _options(value: Any, resolve: Resolver, label: str) -> dict[str, Any]:
    if not isinstance(value, dict):  # the scene checks each option (server.core.physics.dynamics)
        raise WrongType(f"{label}: expected an object of options, got {show(value)}")
    return value


# the kinds whose values name objects of the scene (ownership checks look only at these)
NODE_KINDS = frozenset({"node", "part", "motor", "slot", "contact", "transforms"})

_KINDS: dict[str, Callable[[Any, Resolver, str], Any]] = {
    "number": lambda v, r, label: _number(v, label),
    "size": _size,
    "integer": _integer,
    "limit": lambda v, r, label: _number(v, label, ("Infinity", "-Infinity")),
    "angle": lambda v, r, label: None if v is None else _number(v, label, tuple(NON_FINITE)),
    "bool": _bool,
    "string": _string,
    "asset": _string,  # a mesh filename: the part resolves it (server.core.physics.assets)
    "robotFile": _string,  # an uploaded robot file's name: ImportedRobot resolves it
    "color": _color,
    "rgb": _rgb,
    "axis": _axis,
    "order": _choice(EULER_ORDERS),
    "node": _reference(Robot, Part),
    "part": _reference(Part),
    "motor": _reference(Motor),
    "slot": _slot,
    "laser": _laser,
    "contact": _contact,
    "quaternion": _quaternion,
    "scale": _scale,
    "geometry": _geometry,
    "transforms": _transforms,
    "mode": _choice(MODES),
    "options": _options,
    "mass": _ranged(0.0, 1e9, "a mass (kg)", low_open=True),
    "friction": _ranged(0.0, 10.0, "a friction coefficient"),
    "torque": _ranged(0.0, 1e12, "a torque (N·m)"),
    "speed": _speed,
    "ticks": _ticks,
}


KINDS: frozenset[str] = frozenset(_KINDS) | {"point"}
