"""Hypothesis strategies for protocol messages: valid, almost valid and garbage.

Valid messages are drawn from the API table (:mod:`server.core.protocol.api`), so every type and
method the server offers is exercised with arguments of the right kinds; almost valid
ones are valid ones with one thing broken; garbage is anything at all. Each drawn
message carries the class it was drawn from, so a run can say how many of each it tried.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any, Callable

from hypothesis import strategies as st

from server.core.protocol import api

BIG = 10 ** 4000  # a 4 001-digit integer: JSON carries it, no float does

# Each "Why" case of the hostile-input issue that fits in a message: (client, serial
# number, request id) -> the message's text.
HOSTILE_CASES: dict[str, Callable[[str, int, int], str]] = {
    "ball of radius 0": lambda me, n, i: json.dumps(
        {"op": "create", "object": f"{me}.{n}", "type": "Ball", "args": [0], "id": i}),
    "motor limits both infinite": lambda me, n, i: json.dumps(
        {"op": "create", "object": f"{me}.{n}", "type": "MotorZ",
         "args": ["Infinity", "Infinity"], "id": i}),
    "sensor at 1e308": lambda me, n, i: json.dumps(
        {"op": "batch", "id": i, "ops": [
            {"op": "create", "object": f"{me}.{n}", "type": "Sensor"},
            {"op": "call", "object": f"{me}.{n}", "method": "setPosition",
             "args": [1e308, 0, 0]}]}),
    "4000-digit integer argument": lambda me, n, i: json.dumps(
        {"op": "create", "object": f"{me}.{n}", "type": "Box", "args": [BIG], "id": i}),
    "id of 10^300": lambda me, n, i: json.dumps({"op": "ping", "id": 10 ** 300}),
    "op nested 970 deep": lambda me, n, i: (
        '{"op": "call", "object": "%s.%d", "method": "setAngle", "args": %s, "id": %d}'
        % (me, n, "[" * 970 + "]" * 970, i)),
    "id ending in a newline": lambda me, n, i: json.dumps(
        {"op": "create", "object": f"{me}.{n}\n", "type": "Box", "id": i}),
    "900 KB unknown op": lambda me, n, i: json.dumps({"op": "x" * 900_000, "id": i}),
    "10 000-op batch of boxes": lambda me, n, i: json.dumps(
        {"op": "batch", "id": i, "ops": [
            {"op": "create", "object": f"{me}.{n}x{k}", "type": "Box"} for k in range(10_000)]}),
    "3 000-part chain": lambda me, n, i: json.dumps(
        {"op": "batch", "id": i, "ops": [
            {"op": "create", "object": f"{me}.{n}x{k}", "type": "Box"} for k in range(3000)] + [
            {"op": "call", "object": f"{me}.{n}x{k}", "method": "attachToSlot",
             "args": [{"ref": f"{me}.{n}x{k - 1}"}, 0]} for k in range(1, 3000)]}),
}


@dataclass
class Drawn:
    """One message to send: its text (or bytes), its class, and the id to expect back."""

    kind: str
    data: str | bytes
    answer_id: int | None  # the id the answer must carry (None: no answer is promised)


def numbers(low: float, high: float) -> st.SearchStrategy[float]:
    return st.floats(low, high, allow_nan=False, allow_infinity=False)


def argument(kind: str, refs: list[str]) -> st.SearchStrategy[Any]:
    """A valid argument of a parameter kind of the API table."""
    ref = st.sampled_from(refs).map(lambda r: {"ref": r}) if refs else st.just(None)
    return {
        "number": numbers(-5, 5), "size": numbers(0.01, 3), "integer": st.integers(0, 25),
        "limit": st.one_of(numbers(-3, 3), st.sampled_from(["Infinity", "-Infinity"])),
        "angle": st.one_of(numbers(-4, 4), st.sampled_from(["Infinity", "-Infinity", None])),
        "bool": st.booleans(), "string": st.text(max_size=12),
        "color": st.sampled_from(["red", "#00ff00", "lightgray", 0x336699]),
        "rgb": st.one_of(st.sampled_from(["red", "#00ff00", 0x336699]),
                         st.lists(numbers(0, 1), min_size=3, max_size=3)),
        "asset": st.one_of(st.sampled_from(["round-palm.glb", "../assets/gltf/round-tip.glb",
                                            "/assets/gltf/anthro-thumb.glb"]),
                           st.text(max_size=12)),
        "robotFile": st.one_of(st.just("0123456789abcdef0123456789abcdef.robot"), st.text(max_size=12)),
        "axis": st.one_of(st.sampled_from("xyz"), st.lists(numbers(-1, 1), min_size=3, max_size=3)), "order": st.sampled_from(["XYZ", "ZYX", "YXZ"]),
        "point": st.lists(numbers(-5, 5), min_size=3, max_size=3),
        "node": ref, "part": ref, "motor": ref, "slot": st.one_of(st.integers(0, 6), ref),
        "laser": st.sampled_from([None, True, False, "blue"]),
        "contact": st.one_of(ref, st.just("ground")),
        "quaternion": st.lists(numbers(-1, 1), min_size=4, max_size=4)
        .filter(lambda q: sum(c * c for c in q) > 1e-6),
        "scale": st.lists(numbers(0, 3), min_size=3, max_size=3),
        "geometry": st.one_of(
            st.builds(lambda s: {"kind": "box", "size": s}, st.lists(numbers(0.01, 2), min_size=3, max_size=3)),
            st.builds(lambda r: {"kind": "sphere", "radius": r}, numbers(0.01, 2)),
            st.builds(lambda v: {"kind": "hull", "vertices": v},
                      st.lists(numbers(-2, 2), min_size=12, max_size=30).filter(lambda v: len(v) % 3 == 0)),
            st.builds(lambda v: {"kind": "triangles", "vertices": v},
                      st.lists(numbers(-2, 2), min_size=9, max_size=9))),
        "mode": st.sampled_from(["kinematic", "dynamic"]),
        "options": st.fixed_dictionaries({}, optional={
            "gravity": numbers(-20, 20), "substeps": st.integers(1, 3),
            "solverIterations": st.integers(1, 60), "solverTolerance": numbers(0, 1),
            "friction": numbers(0, 2),
            "density": numbers(1, 5000), "warmStart": numbers(0, 1)}),
        "mass": numbers(0.01, 1000), "friction": numbers(0, 3), "torque": numbers(0, 1e5),
        "speed": st.one_of(numbers(0.01, 10), st.just("Infinity")),
        "transforms": st.dictionaries(st.sampled_from(refs), st.lists(numbers(-1, 1), min_size=7, max_size=7)
                                      .filter(lambda t: sum(c * c for c in t[3:]) > 1e-6), max_size=4)
        if refs else st.just({}),
    }[kind]


def _methods(type_name: str) -> list[api.Method]:
    methods: list[api.Method] = []
    spec: api.TypeSpec | None = api.TYPES[type_name]
    while spec is not None:
        methods += spec.methods
        spec = api.TYPES.get(spec.base) if spec.base else None
    return methods


@st.composite
def arguments(draw: st.DrawFn, params: tuple[api.Param, ...], refs: list[str]) -> list[Any]:
    values = []
    for param in params:
        if param.default is not api.REQUIRED and draw(st.booleans()):
            break  # the rest take their defaults
        count = draw(st.integers(0, 3)) if param.variadic else 1
        values += [draw(argument(param.kind, refs)) for _ in range(count)]
    return values


CREATABLE = sorted(name for name, spec in api.TYPES.items() if spec.creatable)


@st.composite
def valid_op(draw: st.DrawFn, world: dict[str, str], client: str, serial: list[int]) -> dict:
    """A create of any creatable type, or a call of any method of a known object."""
    refs = sorted(world)
    if not refs or draw(st.integers(0, 2)) == 0:
        type_name = draw(st.sampled_from(CREATABLE))
        serial[0] += 1
        object_id = f"{client}.{serial[0]}"
        world[object_id] = type_name  # optimistic: a refused create leaves a dead id
        return {"op": "create", "object": object_id, "type": type_name,
                "args": draw(arguments(api.TYPES[type_name].params, refs))}
    object_id = draw(st.sampled_from(refs))
    if draw(st.integers(0, 12)) == 0:
        return {"op": "delete", "object": object_id}
    method = draw(st.sampled_from(_methods(world[object_id])))
    return {"op": "call", "object": object_id, "method": method.name,
            "args": draw(arguments(method.params, refs))}


JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers() | numbers(-1e300, 1e300) | st.text(max_size=20),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner,
                                                                max_size=4),
    max_leaves=12)
BREAKAGES = ["drop a field", "wrong type for a field", "extra field", "hostile argument",
             "unknown object", "another client's object", "bad id", "unknown op",
             "unknown method", "unknown type"]


@st.composite
def almost_valid(draw: st.DrawFn, op: dict[str, Any], others: list[str]) -> tuple[str, dict]:
    """A valid op with one thing broken; which thing, and the op."""
    broken = dict(op)
    how = draw(st.sampled_from(BREAKAGES))
    if how == "drop a field":
        broken.pop(draw(st.sampled_from(sorted(k for k in broken if k != "op"))), None)
    elif how == "wrong type for a field":
        broken[draw(st.sampled_from(sorted(broken)))] = draw(JSON_VALUES)
    elif how == "extra field":
        broken[draw(st.text(min_size=1, max_size=8))] = draw(JSON_VALUES)
    elif how == "hostile argument":
        hostile = st.sampled_from([BIG, -BIG, 1e308, -0.0, "NaN", "Infinity", None, [],
                                   [[1]], {"ref": "nobody"}, "x" * 5000, True, 2 ** 53])
        args = list(broken.get("args", [])) or [None]
        args[draw(st.integers(0, len(args) - 1))] = draw(hostile)
        broken["args"] = args
    elif how == "unknown object":
        broken["object"] = broken.get("object", "c0.1") + "zz"
    elif how == "another client's object" and others:
        broken["object"] = draw(st.sampled_from(others))
    elif how == "bad id":
        broken["id"] = draw(st.sampled_from([-1, 1.5, "7", None, 2 ** 53, 10 ** 300, []]))
    elif how == "unknown op":
        broken["op"] = draw(st.sampled_from(["crate", "", "CREATE", "__proto__", "x" * 300]))
    elif how == "unknown method":
        broken.update(op="call", method=draw(st.sampled_from(["fly", "constructor",
                                                               "__init__", "setangle"])))
    elif how == "unknown type":
        broken.update(op="create", type=draw(st.sampled_from(["Cube", "Scene", "object",
                                                              "EdgedHand2"])))
    return how, broken


GARBAGE = st.one_of(
    st.text(max_size=200).map(lambda t: ("text", t)),
    JSON_VALUES.map(lambda v: ("any JSON", json.dumps(v))),
    st.binary(max_size=64).map(lambda b: ("binary", b)),
    st.integers(1, 3000).map(lambda n: ("deep nesting", "[" * n + "]" * n)),
    st.just(("over 1 MiB", json.dumps({"op": "ping", "pad": "x" * (1 << 20)}))),
    st.just(("multi-byte over 1 MiB", json.dumps({"op": "ping", "pad": "é" * 600_000},
                                                 ensure_ascii=False))),
)


def is_answerable(message: Any) -> int | None:
    """The id an answer must carry: a whole number below 2^53 in an object that parses."""
    if not isinstance(message, dict):
        return None
    value = message.get("id")
    if isinstance(value, bool) or not isinstance(value, int):
        return None
    return value if 0 <= value <= 2 ** 53 - 1 else None
