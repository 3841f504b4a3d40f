"""Write the API table as ``protocol/api.json`` for the clients: ``python -m server.core.protocol.api_export``."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from ..kit.numbers import encode_numbers
from .api import REQUIRED, TYPES, Param, snake

API_PATH = Path(__file__).resolve().parents[3] / "protocol" / "api.json"


def _param(param: Param) -> dict[str, Any]:
    out: dict[str, Any] = {"name": param.name, "kind": param.kind}
    if param.variadic:
        out["variadic"] = True
    elif param.default is not REQUIRED:
        out["default"] = encode_numbers(param.default)
    return out


def table() -> dict[str, Any]:
    """The API table as JSON-ready data."""
    return {"protocol": 1, "types": {
        spec.name: {"extends": spec.base, "creatable": spec.creatable, "slots": spec.slots,
                    "params": [_param(p) for p in spec.params],
                    "methods": {m.name: {"python": m.python, "params": [_param(p) for p in m.params],
                                         "returns": m.returns, "mutates": m.mutates,
                                         "access": m.access}
                                for m in spec.methods},
                    "callbacks": {c: snake(c) for c in spec.callbacks}}
        for spec in TYPES.values()}}


def render() -> str:
    """The text of ``protocol/api.json``."""
    return json.dumps(table(), indent=1) + "\n"


if __name__ == "__main__":
    API_PATH.write_text(render())
    print(f"wrote {API_PATH}")
