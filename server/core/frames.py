"""Folding two frames into one, for a connection that cannot keep up."""

from __future__ import annotations

from typing import Any

_LATEST_WINS = ("angles", "poses", "sensors")


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
    if "contacts" in older:  # events: every one is kept, in order
        later = newer.get("contacts", {"begin": [], "end": []})
        merged["contacts"] = _merge_contacts(older["contacts"], later)
    if "camera" in older and "camera" not in newer:
        merged["camera"] = older["camera"]
    return merged


def _merge_contacts(older: dict[str, list], newer: dict[str, list]) -> dict[str, list]:
    """Contact changes of two ticks as one: a pair that began and ended again cancels out."""
    begin = [p for p in older["begin"] if p not in newer["end"]]
    end = [p for p in older["end"] if p not in newer["begin"]]
    begin += [p for p in newer["begin"] if p not in older["end"]]
    end += [p for p in newer["end"] if p not in older["begin"]]
    return {"begin": sorted(begin), "end": sorted(end)}
