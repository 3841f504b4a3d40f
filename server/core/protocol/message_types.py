"""Typed definitions of the wire messages, written from ``protocol/schema/protocol.json``:
``python -m server.core.protocol.message_types`` writes the server's
(``server/core/kit/wire_messages.py``), the Python client's
(``clients/python/virtual_prosthetics/wire_messages.py``) and the JavaScript client's
(``clients/js/wire_messages.js``, JSDoc typedefs and the op lists). The schema stays the one
source; tests fail when a written file and the schema differ.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from .messages import schema

ROOT = Path(__file__).resolve().parents[3]
TARGETS = [ROOT / "server" / "core" / "kit" / "wire_messages.py",
           ROOT / "clients" / "python" / "virtual_prosthetics" / "wire_messages.py"]
JS_TARGET = ROOT / "clients" / "js" / "wire_messages.js"
PLAIN = {"string": "str", "integer": "int", "number": "float", "boolean": "bool", "null": "None"}
HEADER = '''"""One typed definition per wire message. Written by
``python -m server.core.protocol.message_types`` from protocol/schema/protocol.json; do
not edit (a test fails when the two differ).

Messages stay plain dicts on the wire and in the code: ``Frame(op="frame", seq=1, time=0.0)``
makes one; the definitions say which keys each has, for readers and type checkers.
"""

# (no `from __future__ import annotations`: TypedDict reads NotRequired from the
# evaluated annotations)
from typing import Any, Literal, NotRequired, TypedDict
'''


def python_type(spec: Any, defs: dict[str, Any]) -> str:
    """The Python type of a JSON Schema value (what the schema leaves open is ``Any``)."""
    if not isinstance(spec, dict):
        return "Any"
    if "$ref" in spec:
        name = spec["$ref"].removeprefix("#/$defs/")
        return python_type(defs[name], defs) if "/" not in name else "Any"
    if "const" in spec:
        return f"Literal[{spec['const']!r}]"
    if "enum" in spec:
        return "str" if all(isinstance(v, str) for v in spec["enum"]) else "Any"
    if "oneOf" in spec:
        return " | ".join(dict.fromkeys(python_type(s, defs) for s in spec["oneOf"]))
    kind = spec.get("type")
    if kind == "array":
        return f"list[{python_type(spec.get('items'), defs)}]"
    if kind == "object":
        return f"dict[str, {python_type(spec.get('additionalProperties'), defs)}]"
    return PLAIN.get(kind, "Any") if isinstance(kind, str) else "Any"


def class_name(op: str) -> str:
    return "WarningMessage" if op == "warning" else op.capitalize()


def definition(op: str, defs: dict[str, Any]) -> str:
    spec = defs[op]
    lines = [f"class {class_name(op)}(TypedDict):"]
    for key, value in spec["properties"].items():
        kind = python_type(value, defs)
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


JS_PLAIN = {"string": "string", "integer": "number", "number": "number", "boolean": "boolean",
            "null": "null"}
JS_HEADER = """// One typed definition (a JSDoc typedef) per wire message, and the op lists. Written by
// `python -m server.core.protocol.message_types` from protocol/schema/protocol.json; do
// not edit (a test fails when the two differ). Messages stay plain objects: messages.js
// makes the ones a client sends, protocol.js checks the ops of those a server sends."""


def js_type(spec: Any, defs: dict[str, Any]) -> str:
    """The JSDoc type of a JSON Schema value (what the schema leaves open is ``*``)."""
    if not isinstance(spec, dict):
        return "*"
    if "$ref" in spec:
        name = spec["$ref"].removeprefix("#/$defs/")
        return js_type(defs[name], defs) if "/" not in name else "*"
    if "const" in spec:
        return repr(spec["const"]) if isinstance(spec["const"], str) else "*"
    if "enum" in spec:
        return "string" if all(isinstance(v, str) for v in spec["enum"]) else "*"
    if "oneOf" in spec:
        return "(" + "|".join(dict.fromkeys(js_type(s, defs) for s in spec["oneOf"])) + ")"
    kind = spec.get("type")
    if kind == "array":
        return f"Array<{js_type(spec.get('items'), defs)}>"
    if kind == "object":
        return f"Object<string, {js_type(spec.get('additionalProperties'), defs)}>"
    return JS_PLAIN.get(kind, "*") if isinstance(kind, str) else "*"


def js_definition(op: str, defs: dict[str, Any]) -> str:
    spec = defs[op]
    lines = ["/**", f" * @typedef {{object}} {class_name(op)}"]
    for key, value in spec["properties"].items():
        name = key if key in spec["required"] else f"[{key}]"
        lines.append(f" * @property {{{js_type(value, defs)}}} {name}")
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


def written() -> dict[Path, str]:
    """Every written file and the text it should hold."""
    text = render()
    return {**{target: text for target in TARGETS}, JS_TARGET: render_js()}


if __name__ == "__main__":
    for target, text in written().items():
        target.write_text(text)
        print(f"wrote {target}")
