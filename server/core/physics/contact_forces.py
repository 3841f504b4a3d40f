"""Forces at contacts in dynamic mode, read from Bullet's contact points of the last step.

Bullet reports each contact point with its normal force and two friction forces along
directions of its own choosing; a part's pressing force is the sum of its points' normal
forces, and its friction from one other body the length of the summed friction vectors
(opposite frictions at two corners of a face cancel, as they do on the part).
"""

from __future__ import annotations

import math
from typing import Any, Collection, Mapping, NamedTuple, Sequence

# Bullet's contact point: (flag, bodyA, bodyB, linkA, linkB, onA, onB, normalOnB, distance,
# normalForce, lateralFriction1, lateralFrictionDir1, lateralFriction2, lateralFrictionDir2)
BODY_A, BODY_B, LINK_A, LINK_B, NORMAL = 1, 2, 3, 4, 9
FRICTION_1, DIRECTION_1, FRICTION_2, DIRECTION_2 = 10, 11, 12, 13
KeysOf = Mapping[int, Sequence["str | None"]]  # body -> the part of each link, the base's last


class ContactForce(NamedTuple):
    """What one other body (a part's id, or "ground") does to a part: its normal force
    and its friction force, in newtons."""

    other: str
    normal: float
    friction: float

    def wire(self) -> dict[str, Any]:
        """As frames and answers carry it (to 1 mN)."""
        return {"other": self.other, "normal": round(self.normal, 3),
                "friction": round(self.friction, 3)}


def forces_by_part(points: Sequence[Sequence[Any]], keys_of: KeysOf,
                   newtons: float = 1.0) -> dict[str, float]:
    """Newtons pressing on each part: the normal forces of its contact points, summed
    (``newtons`` in one of Bullet's units of force)."""
    found: dict[str, float] = {}
    for point in points:
        force = point[NORMAL] * newtons
        if force > 0.0:
            for key in (keys_of[point[BODY_A]][point[LINK_A]], keys_of[point[BODY_B]][point[LINK_B]]):
                if key is not None:
                    found[key] = found.get(key, 0.0) + force
    return found


def contacts_by_part(points: Sequence[Sequence[Any]], keys_of: KeysOf, wanted: Collection[str],
                     newtons: float = 1.0) -> dict[str, tuple[ContactForce, ...]]:
    """For each part of ``wanted`` that something presses on: a :class:`ContactForce` per
    other body, the largest normal force first. One pass over the points (a tick reads
    every watched sensor's at once); bodies no longer in ``keys_of`` are passed over."""
    sums: dict[tuple[str, str], list[float]] = {}  # (part, other): normal, friction x, y, z
    for point in points:
        if point[NORMAL] <= 0.0:
            continue
        a_keys, b_keys = keys_of.get(point[BODY_A]), keys_of.get(point[BODY_B])
        if a_keys is None or b_keys is None:
            continue
        a, b = a_keys[point[LINK_A]], b_keys[point[LINK_B]]
        for part, other, sign in ((a, b, 1.0), (b, a, -1.0)):
            if part in wanted and other is not None:
                _add(sums.setdefault((part, other), [0.0] * 4), point, sign)
    found: dict[str, list[ContactForce]] = {}
    for (part, other), (normal, *friction) in sums.items():
        found.setdefault(part, []).append(ContactForce(
            other, normal * newtons, math.hypot(*friction) * newtons))
    return {part: tuple(sorted(forces, key=lambda f: -f.normal)) for part, forces in found.items()}


def _add(sums: list[float], point: Sequence[Any], sign: float) -> None:
    """One point's normal force and friction vector (as felt by body A when ``sign`` is 1,
    by body B when it is -1) into ``sums``."""
    sums[0] += point[NORMAL]
    f1, f2, d1, d2 = point[FRICTION_1], point[FRICTION_2], point[DIRECTION_1], point[DIRECTION_2]
    for axis in range(3):
        sums[1 + axis] += sign * (f1 * d1[axis] + f2 * d2[axis])
