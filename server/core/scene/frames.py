"""A tick's messages, and two frames folded into one for a connection that cannot keep up:
the one module that knows a frame's whole shape.

A frame has ``op``, ``seq`` and ``time``, and what changed in its tick: ``angles`` (a
robot's angles as one array in the order of its ``motors``, by the robot's id; a motor
that is no robot's, by its own id), ``poses`` (node id -> value), ``updates`` (node id ->
fields), ``sensors`` (watched sensor id -> reading), ``contacts`` (``begin``/``end`` lists
of pairs, events), ``forces`` (dynamic mode: part id -> newtons pressing on it, for the
parts whose force changed; 0 once it ends), ``camera``, ``physics``, ``caption`` and
``limited`` (limit name -> how much work it held back in the tick). New nodes travel
before it in ``added``, removed ones after it in ``removed``.
"""

from __future__ import annotations

from operator import attrgetter
from typing import Any, Mapping

from ..kit.numbers import encode_numbers
from ..kit.wire_messages import Added, Frame, Removed
from ..model.node import Node
from .changes import ChangeSet

_LATEST_WINS = ("angles", "poses", "sensors", "forces")
SCENE_FIELDS = ("camera", "physics", "caption")  # the scene's own, each sent whole
_ANGLE = attrgetter("angle")


def tick_messages(seq: int, time: float, changes: dict[str, Any]) -> list[Added | Frame | Removed]:
    """The messages of tick ``seq``: its ``added`` nodes, its frame, its ``removed`` ids."""
    fields = dict(changes)
    added, removed = fields.pop("added", None), fields.pop("removed", None)
    return [*([Added(op="added", seq=seq, nodes=added)] if added else []),
            Frame(op="frame", seq=seq, time=time, **fields),
            *([Removed(op="removed", seq=seq, ids=removed)] if removed else [])]


def changes_wire(nodes: Mapping[str, Node], changes: ChangeSet,
                 scene_fields: Mapping[str, Any]) -> dict[str, Any]:
    """What a change set amounts to now, in wire form (empty parts left out but a caption
    made empty): a frame's ``angles``, ``poses``, ``updates`` and the changed scene-level
    ``scene_fields`` (``camera``, ``physics``, ``caption``), with ``added`` and ``removed``."""
    born = changes.born
    out: dict[str, Any] = {
        "added": [encode_numbers(nodes[i].describe()) for i in born if i in nodes],
        "angles": _angles(nodes, changes),
        "poses": {i: [*nodes[i].position, *nodes[i].quaternion] for i in changes.poses
                  if i in nodes and i not in born},
        "updates": {i: {WIRE_NAMES.get(f, f): _field(nodes[i], f) for f in sorted(fields)}
                    for i, fields in changes.updates.items() if i in nodes and i not in born},
        "removed": [i for i in changes.died if i not in nodes and i not in born],
    }
    return {**{k: v for k, v in out.items() if v}, **scene_fields}


def _angles(nodes: Mapping[str, Node], changes: ChangeSet) -> dict[str, Any]:
    """The ``angles`` of a change set: every robot with a turned motor, or whose motor list
    changed, as the array of all its angles (so a merged frame's newest array always
    matches the newest list); other motors one by one. A motor that left a robot is noted
    as turned (Scene.reparented), so the frame that changes the list sends it too."""
    born, out = changes.born, {}
    robots: dict[str, list[Any]] = {}
    covered: set[str] = set(born)  # motors of the robots found: their roots are not looked up
    for i in changes.angles:
        if i in covered or (node := nodes.get(i)) is None:
            continue
        root = node.root()
        if not root.lists_motors:
            out[i] = node.angle
        elif root.id not in robots:
            robots[root.id] = root.get_motors()  # type: ignore[attr-defined]
            covered |= root.motor_ids()  # type: ignore[attr-defined]
    for i, fields in changes.updates.items():
        if "motors" in fields and i in nodes and i not in born:
            robots[i] = nodes[i].get_motors()  # type: ignore[attr-defined]
    for i, motors in robots.items():
        out[i] = list(map(_ANGLE, motors))
    return out


# the node attributes whose wire name (describe()'s) is not their own
WIRE_NAMES = {"max_torque": "maxTorque", "max_speed": "maxSpeed"}


def _field(node: Node, field: str) -> Any:
    if field == "max_torque":
        return node.get_max_torque()  # type: ignore[attr-defined]
    if field == "max_speed":
        return encode_numbers(node.get_max_speed())  # type: ignore[attr-defined]
    if field == "parent":
        return node.parent.id if node.parent is not None else None
    if field == "children":
        return [child.id for child in node.children]
    return encode_numbers(getattr(node, field))


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
    for key in SCENE_FIELDS:
        if key in older and key not in newer:
            merged[key] = older[key]
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
