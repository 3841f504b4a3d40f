"""Typed definitions of the wire messages, written from ``protocol/schema/protocol.json``:
``python -m server.core.protocol.message_types`` writes the server's
(``server/core/kit/wire_messages.py``) and the Python client's
(``clients/python/virtual_prosthetics/wire_messages.py``). The schema stays the one source;
tests fail when a written file and the schema differ.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .messages import schema

ROOT = Path(__file__).resolve().parents[3]
TARGETS = [ROOT / "server" / "core" / "kit" / "wire_messages.py",
           ROOT / "clients" / "python" / "virtual_prosthetics" / "wire_messages.py"]
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


if __name__ == "__main__":
    text = render()
    for target in TARGETS:
        target.write_text(text)
        print(f"wrote {target}")
