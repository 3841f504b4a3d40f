"""The API table (:mod:`server.core.protocol.api`) as ``protocol/api.json``, for the clients."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from server.core.kit.numbers import encode_numbers
from server.core.protocol.api import REQUIRED, TYPES, Param, snake

API_PATH = Path(__file__).resolve().parents[1] / "protocol" / "api.json"


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



def outputs() -> dict[Path, str]:
    """What this generator writes."""
    return {API_PATH: render()}
