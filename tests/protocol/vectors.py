"""Loading the shared test vectors of protocol/vectors and matching answers against them."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

VECTORS = Path(__file__).resolve().parents[2] / "protocol" / "vectors"


def vector_files() -> list[Path]:
    return sorted(VECTORS.glob("*.json"))


def substitute(value: Any, client: str) -> Any:
    """The vector value with {client} replaced by the real client id."""
    if isinstance(value, str):
        return value.replace("{client}", client)
    if isinstance(value, list):
        return [substitute(v, client) for v in value]
    if isinstance(value, dict):
        return {substitute(k, client): substitute(v, client) for k, v in value.items()}
    return value


def steps(path: Path, client: str) -> list[tuple[str, list[Any]]]:
    """(text to send, expected answers) for each step of a vector file."""
    out = []
    for step in json.loads(path.read_text())["steps"]:
        text = step["sendText"] if "sendText" in step else json.dumps(step["send"])
        out.append((text.replace("{client}", client), substitute(step["expect"], client)))
    return out


def mismatch(expected: Any, actual: Any, where: str = "answer") -> str | None:
    """Where ``actual`` breaks the pattern ``expected`` (dicts: a subset of keys; "$any")."""
    if expected == "$any":
        return None
    if isinstance(expected, dict):
        if not isinstance(actual, dict):
            return f"{where}: expected an object, got {actual!r}"
        for key, value in expected.items():
            if key not in actual:
                return f"{where}: missing {key!r} in {actual!r}"
            problem = mismatch(value, actual[key], f"{where}.{key}")
            if problem:
                return problem
        return None
    if isinstance(expected, list):
        if not isinstance(actual, list) or len(actual) != len(expected):
            return f"{where}: expected {len(expected)} items, got {actual!r}"
        for i, (e, a) in enumerate(zip(expected, actual)):
            problem = mismatch(e, a, f"{where}[{i}]")
            if problem:
                return problem
        return None
    if isinstance(expected, (int, float)) and not isinstance(expected, bool):
        ok = isinstance(actual, (int, float)) and not isinstance(actual, bool) and \
            math.isclose(expected, actual, rel_tol=1e-9, abs_tol=1e-12)
        return None if ok else f"{where}: expected {expected!r}, got {actual!r}"
    return None if expected == actual else f"{where}: expected {expected!r}, got {actual!r}"
