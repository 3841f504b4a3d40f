"""A tick's messages, and two frames folded into one for a connection that cannot keep up:
the one module that knows a frame's whole shape.

A frame has ``op``, ``seq`` and ``time``, and what changed in its tick: ``angles`` and
``poses`` (node id -> value), ``updates`` (node id -> fields), ``sensors`` (watched sensor id
-> reading), ``contacts`` (``begin``/``end`` lists of pairs, events), ``camera`` and
``limited`` (limit name -> how much work it held back in the tick). New nodes travel before
it in ``added``, removed ones after it in ``removed``.
"""

from __future__ import annotations

from typing import Any

from ..kit.wire_messages import Added, Frame, Removed

_LATEST_WINS = ("angles", "poses", "sensors")


def tick_messages(seq: int, time: float, changes: dict[str, Any]) -> list[Added | Frame | Removed]:
    """The messages of tick ``seq``: its ``added`` nodes, its frame, its ``removed`` ids."""
    fields = dict(changes)
    added, removed = fields.pop("added", None), fields.pop("removed", None)
    return [*([Added(op="added", seq=seq, nodes=added)] if added else []),
            Frame(op="frame", seq=seq, time=time, **fields),
            *([Removed(op="removed", seq=seq, ids=removed)] if removed else [])]


def held_back(**counts: int) -> dict[str, Any]:
    """A frame's ``limited`` field for the limits that held work back (none: no field)."""
    limited = {limit: count for limit, count in counts.items() if count}
    return {"limited": limited} if limited else {}


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
    if "limited" in older:  # what the limits held back in the worse of the two ticks
        both = (older["limited"], newer.get("limited", {}))
        merged["limited"] = {k: max(side.get(k, 0) for side in both) for k in {**both[0], **both[1]}}
    return merged


def _merge_contacts(older: dict[str, list], newer: dict[str, list]) -> dict[str, list]:
    """Contact changes of two ticks as one: a pair that began and ended again cancels out."""
    begin = [p for p in older["begin"] if p not in newer["end"]]
    end = [p for p in older["end"] if p not in newer["begin"]]
    begin += [p for p in newer["begin"] if p not in older["end"]]
    end += [p for p in newer["end"] if p not in older["begin"]]
    return {"begin": sorted(begin), "end": sorted(end)}
