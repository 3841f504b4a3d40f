"""Folding two frames into one, for a connection that cannot keep up."""

from __future__ import annotations

from typing import Any

_LATEST_WINS = ("angles", "poses")


def merge_frames(older: dict[str, Any], newer: dict[str, Any]) -> dict[str, Any]:
    """One frame that has the effect of ``older`` followed by ``newer``."""
    merged = dict(newer)
    for key in _LATEST_WINS:
        if key in older:
            merged[key] = {**older[key], **newer.get(key, {})}
    if "updates" in older:
        updates = {node: dict(fields) for node, fields in older["updates"].items()}
        for node, fields in newer.get("updates", {}).items():
            updates.setdefault(node, {}).update(fields)
        merged["updates"] = updates
    if "camera" in older and "camera" not in newer:
        merged["camera"] = older["camera"]
    return merged
