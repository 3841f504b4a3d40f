"""How values the JSON standard cannot carry travel: non-finite numbers as strings."""

from __future__ import annotations

import math
from typing import Any

NON_FINITE: dict[str, float] = {"Infinity": math.inf, "-Infinity": -math.inf, "NaN": math.nan}


def wire_number(value: float) -> float | str:
    """A number as it travels: finite ones as they are, others as "Infinity", "-Infinity", "NaN"."""
    if math.isfinite(value):
        return value
    if math.isnan(value):
        return "NaN"
    return "Infinity" if value > 0 else "-Infinity"


class Finite(tuple):  # type: ignore[type-arg]
    """Numbers (or nested tuples of them) known to be finite, such as a part's geometry:
    :func:`encode_numbers` passes them as they are instead of looking at each."""


def encode_numbers(value: Any) -> Any:
    """``value`` with every non-finite float inside it replaced by its wire string."""
    if isinstance(value, Finite):
        return value
    if isinstance(value, float):
        return wire_number(value)
    if isinstance(value, dict):
        return {k: encode_numbers(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [encode_numbers(v) for v in value]
    return value
