"""Numbers and objects as they travel (protocol/README.md), the one place in Python.

JSON has no Infinity or NaN: they travel as the strings ``"Infinity"``, ``"-Infinity"``
and ``"NaN"``. Objects travel as ``{"ref": id}``.
"""

from __future__ import annotations

import json
import math
from typing import Any

NON_FINITE = {"Infinity": math.inf, "-Infinity": -math.inf, "NaN": math.nan}


def wire_number(x: float) -> float | str:
    """A number as it travels: finite ones as they are, the others as their strings."""
    if math.isfinite(x):
        return x
    return "NaN" if math.isnan(x) else ("Infinity" if x > 0 else "-Infinity")


def from_wire(value: Any) -> Any:
    """A wire string for a non-finite number back to its float; anything else unchanged."""
    return NON_FINITE.get(value, value) if isinstance(value, str) else value


def encode_arg(value: Any) -> Any:
    """An argument as it travels: objects as {"ref": id}, non-finite numbers as strings."""
    if hasattr(value, "_scene") and hasattr(value, "id"):
        return {"ref": value.id}
    if isinstance(value, float):
        return wire_number(value)
    if isinstance(value, (list, tuple)):
        return [encode_arg(v) for v in value]
    return value


def encode(message: dict[str, Any]) -> str:
    """One message as the text the server takes (a bare Infinity is refused there)."""
    return json.dumps(message, allow_nan=False, separators=(",", ":"))


def decode(text: str | bytes) -> Any:
    """A server message (its non-finite numbers are strings, kept as such here)."""
    return json.loads(text)
