"""Typed definitions of the wire messages, written from ``protocol/schema/protocol.json``:
``make generate`` writes the server's
(``server/core/kit/wire_messages.py``), the Python client's
(``clients/python/virtual_prosthetics/wire_messages.py``) and the JavaScript client's
(``clients/js/wire_messages.js``, JSDoc typedefs and the op lists). The schema stays the one
source; tests fail when a written file and the schema differ.
"""

from __future__ import annotations

import json
from pathlib import Path
from dataclasses import dataclass
from typing import Any, Callable

from server.core.protocol.messages import schema

ROOT = Path(__file__).resolve().parents[1]
TARGETS = [ROOT / "server" / "core" / "kit" / "wire_messages.py",
           ROOT / "clients" / "python" / "virtual_prosthetics" / "wire_messages.py"]
JS_TARGET = ROOT / "clients" / "js" / "wire_messages.js"
HEADER = '''"""One typed definition per wire message. Written by ``make generate``
(generate/message_types.py) from protocol/schema/protocol.json; do not edit (a test
fails when the two differ).

Messages stay plain dicts on the wire and in the code: ``Frame(op="frame", seq=1, time=0.0)``
makes one; the definitions say which keys each has, for readers and type checkers.
"""

# (no `from __future__ import annotations`: TypedDict reads NotRequired from the
# evaluated annotations)
from typing import Any, Literal, NotRequired, TypedDict
'''


@dataclass(frozen=True)
class Notation:
    """How one language writes the types of the schema's values."""

    plain: dict[str, str]  # JSON Schema type -> the language's
    open: str  # what the schema leaves open
    literal: Callable[[str], str]
    union: Callable[[list[str]], str]
    array: str  # with {} for the item type
    mapping: str  # with {} for the value type


PYTHON = Notation({"string": "str", "integer": "int", "number": "float", "boolean": "bool",
                   "null": "None"}, "Any", lambda value: f"Literal[{value!r}]",
                  " | ".join, "list[{}]", "dict[str, {}]")
JAVASCRIPT = Notation({"string": "string", "integer": "number", "number": "number",
                       "boolean": "boolean", "null": "null"}, "*", repr,
                      lambda kinds: "(" + "|".join(kinds) + ")", "Array<{}>", "Object<string, {}>")


def type_of(spec: Any, defs: dict[str, Any], notation: Notation = PYTHON) -> str:
    """The type of a JSON Schema value in a language's notation."""
    if not isinstance(spec, dict):
        return notation.open
    if "$ref" in spec:
        name = spec["$ref"].removeprefix("#/$defs/")
        return type_of(defs[name], defs, notation) if "/" not in name else notation.open
    if "const" in spec:
        return notation.literal(spec["const"])
    if "enum" in spec:
        strings = all(isinstance(v, str) for v in spec["enum"])
        return notation.plain["string"] if strings else notation.open
    if "oneOf" in spec:
        return notation.union(list(dict.fromkeys(type_of(s, defs, notation) for s in spec["oneOf"])))
    kind = spec.get("type")
    if kind == "array":
        return notation.array.format(type_of(spec.get("items"), defs, notation))
    if kind == "object":
        return notation.mapping.format(type_of(spec.get("additionalProperties"), defs, notation))
    return notation.plain.get(kind, notation.open) if isinstance(kind, str) else notation.open


def class_name(op: str) -> str:
    return "WarningMessage" if op == "warning" else op.capitalize()


def definition(op: str, defs: dict[str, Any]) -> str:
    spec = defs[op]
    lines = [f"class {class_name(op)}(TypedDict):"]
    for key, value in spec["properties"].items():
        kind = type_of(value, defs)
        lines.append(f"    {key}: {kind if key in spec['required'] else f'NotRequired[{kind}]'}")
    return "\n".join(lines)


def render() -> str:
    """The text of every written file."""
    defs = schema()["$defs"]
    parts = [HEADER.rstrip("\n")]
    tables = []
    for side in ("clientMessage", "serverMessage"):
        ops = defs[side]["properties"]["op"]["enum"]
        parts += [definition(op, defs) for op in ops]
        entries = ", ".join(f'"{op}": {class_name(op)}' for op in ops)
        table = "CLIENT_MESSAGES" if side == "clientMessage" else "SERVER_MESSAGES"
        tables.append(f"{table}: dict[str, type] = {{{entries}}}")
    return "\n\n\n".join(parts + ["\n".join(tables)]) + "\n"


JS_HEADER = """// One typed definition (a JSDoc typedef) per wire message, and the op lists. Written by
// `make generate` (generate/message_types.py) from protocol/schema/protocol.json; do not
// edit (a test fails when the two differ). Messages stay plain objects: messages.js
// makes the ones a client sends, protocol.js checks the ops of those a server sends."""


def js_definition(op: str, defs: dict[str, Any]) -> str:
    spec = defs[op]
    lines = ["/**", f" * @typedef {{object}} {class_name(op)}"]
    for key, value in spec["properties"].items():
        name = key if key in spec["required"] else f"[{key}]"
        lines.append(f" * @property {{{type_of(value, defs, JAVASCRIPT)}}} {name}")
    return "\n".join(lines + [" */"])


def render_js() -> str:
    """The text of the JavaScript client's definitions."""
    defs = schema()["$defs"]
    parts, tables = [JS_HEADER], []
    for side, table in (("clientMessage", "CLIENT_OPS"), ("serverMessage", "SERVER_OPS")):
        ops = defs[side]["properties"]["op"]["enum"]
        parts += [js_definition(op, defs) for op in ops]
        tables.append(f"export const {table} = Object.freeze({json.dumps(ops)});")
    return "\n\n".join(parts + ["\n".join(tables)]) + "\n"


def outputs() -> dict[Path, str]:
    """What this generator writes."""
    text = render()
    return {**{target: text for target in TARGETS}, JS_TARGET: render_js()}

