"""Dynamic mode: links of one robot that overlap in the pose it is built in never collide
with each other.

A robot's links meet each other in dynamic mode (a finger must not pass through the palm),
except the links each hangs from (Bullet's ``URDF_USE_SELF_COLLISION_EXCLUDE_ALL_PARENTS``).
Links that already overlap where they were built (parts put on the same slot, a chain
folded onto itself) would be pushed apart by the solver every step, and each such pair
brings several contacts whose rows span the whole tree: a robot of 112 links whose parts
were stacked on few slots had 2 200-3 600 contacts with itself, and one step took 5-22 s
with a single solver iteration. MoveIt's setup assistant does the same for a robot's
default pose (pairs in collision there are disabled); Bullet offers the per-pair switch
(``setCollisionFilterPair``) but not the search, which is this module: boxes first, then
Bullet's own closest points for the pairs whose boxes meet. A robot with more than PAIRS
such pairs is built without collisions between its own links at all.
"""

from __future__ import annotations

import logging
from typing import Any, Mapping, Sequence

import numpy as np

from .articulation import Articulation

log = logging.getLogger(__name__)
DEPTH = 1e-4  # deeper than this (touching is no overlap: resting faces stay solid)
# Bullet takes 2.6 ms to switch one pair off, whatever the world: past this many pairs the
# robot is built again without collisions between its own links (a pile of parts, not a
# hand: a hand's overlapping pairs are a few fingers' roots)
PAIRS = 24


def dynamic_body(pybullet: Any, client: int, tree: Articulation, arguments: dict[str, Any],
                 angles: Mapping[str, float]) -> tuple[int, int]:
    """The multibody of ``tree`` (``createMultiBody``'s ``arguments``) for dynamic mode: a
    link never meets the links it hangs from (they touch where they are joined, and the
    solver would push the joint apart), nor the links it overlaps at ``angles``; and how
    many were made and removed on the way (0, or 1 for a heap of parts)."""
    flags = pybullet.URDF_USE_SELF_COLLISION | pybullet.URDF_USE_SELF_COLLISION_EXCLUDE_ALL_PARENTS
    body = pybullet.createMultiBody(physicsClientId=client, flags=flags, **arguments)
    joints = list(tree.joints())
    if joints:
        pybullet.resetJointStatesMultiDof(body, [k for k, _ in joints],
                                          [[angles[joint.motor]] for _, joint in joints],
                                          physicsClientId=client)
    pairs = overlapping_pairs(pybullet, client, body, [link.parent for link in tree.links])
    if len(pairs) <= PAIRS:
        exclude(pybullet, client, body, pairs)
        return body, 0
    log.info("%s: %d pairs of its links overlap; its links do not meet each other",
             tree.root, len(pairs))
    pybullet.removeBody(body, physicsClientId=client)
    return pybullet.createMultiBody(physicsClientId=client, **arguments), 1


def overlapping_pairs(pybullet: Any, client: int, body: int,
                      parents: Sequence[int]) -> list[tuple[int, int]]:
    """The links of ``body`` (``parents[k]``: link k's parent, -1 the base) that overlap
    now and are not one below the other."""
    links = list(range(-1, len(parents)))
    boxes = np.array([pybullet.getAABB(body, link, physicsClientId=client) for link in links])
    low, high = boxes[:, 0], boxes[:, 1]
    meet = np.all((low[:, None, :] < high[None, :, :]) & (low[None, :, :] < high[:, None, :]),
                  axis=2)
    lines = _lines(parents)
    pairs = []
    for a, b in zip(*np.nonzero(np.triu(meet, 1))):
        first, second = links[a], links[b]
        if first in lines[second] or second in lines[first]:
            continue  # (never paired: Bullet leaves a link's parents out)
        points = pybullet.getClosestPoints(body, body, 0.0, first, second,
                                           physicsClientId=client)
        if any(point[8] < -DEPTH for point in points):
            pairs.append((first, second))
    return pairs


def exclude(pybullet: Any, client: int, body: int, pairs: list[tuple[int, int]]) -> None:
    """Switch off collisions between these pairs of the body's links."""
    for first, second in pairs:
        pybullet.setCollisionFilterPair(body, body, first, second, 0, physicsClientId=client)


def _lines(parents: Sequence[int]) -> dict[int, set[int]]:
    """Each link's ancestors (the base, -1, has none)."""
    lines: dict[int, set[int]] = {-1: set()}
    for link, parent in enumerate(parents):  # (a parent comes before its children)
        lines[link] = lines[parent] | {parent}
    return lines
