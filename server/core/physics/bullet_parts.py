"""Parts as Bullet holds them, and what Bullet measures of them.

Every physical part is the base or a link of its tree's multibody (:mod:`.engine`):
:class:`BulletParts` knows which, and what pads each shape, and measures by part.

Contacts are those of the exact shapes, the collision margin that pads convex hulls
(``CONVEX_MARGIN``) subtracted again. :meth:`BulletParts.detect` runs Bullet's own pair
processing (broadphase and narrowphase in C++) over the parts it pairs; manifold points
that drift beyond ``BREAKING_THRESHOLD`` (:mod:`.engine`) are dropped, so a part placed
elsewhere keeps no stale point, and a pair that begins is confirmed with
``getClosestPoints`` (:meth:`BulletParts.touching_many`), which also measures, one by one,
the pairs of parts kept out of Bullet's pairing in a crowd. :mod:`.contacts` decides which.
"""

from __future__ import annotations

import math
from typing import Any, Collection, Sequence

from ..kit.math3d import Pose, Vec3
from .bullet import pybullet
from .contact_forces import ContactForce, contacts_by_part, forces_by_part
from .dynamics import Dynamics
from .filter_groups import BODY_GROUP, BODY_MASK, CROWD_GROUP, CROWD_MASK

GROUND = "ground"
CONVEX_MARGIN = 0.001  # PyBullet pads every convex mesh shape by this much
TOUCH_TOLERANCE = 1e-9  # shapes this close count as touching (rounding, not geometry)
NAMED_POINTS = 20_000  # contact points' names kept (detect): beyond, they are named anew

Place = tuple[str, int, dict[str, Any]]  # a part's key, its link (-1: the base), geometry


class BulletParts:
    """Where each part is in one PyBullet client (its body and link; -1: the base), and
    Bullet's measures of parts: the pairs it finds touching, exact touching, poses and
    boxes; in dynamic mode, the forces of the last step."""

    def __init__(self) -> None:
        self.forces: dict[str, float] = {}  # dynamic mode: newtons on each part, last step
        self._points: list[Any] = []  # dynamic mode: Bullet's contact points of the last step
        self._client = -1
        self._dynamics: Dynamics | None = None
        self._where: dict[str, tuple[int, int]] = {}  # part id -> (body, link); -1: the base
        self._keys_of: dict[int, list[str | None]] = {}  # body -> each link's part, the base's last
        self._padding: dict[str, float] = {}
        # Bullet's (body a, body b, link a, link b) -> the pair of parts, its reach (detect)
        self._named: dict[tuple[int, int, int, int], tuple[tuple[str, str], float]] = {}

    def connect(self, client: int, ground: int, dynamics: Dynamics | None) -> None:
        """A fresh client's: the ground alone (every part is added again)."""
        self._client, self._dynamics = client, dynamics
        self.forces, self._points = {}, []
        self._where, self._keys_of, self._padding = {GROUND: (ground, -1)}, {ground: [GROUND]}, {GROUND: 0.0}
        self._named = {}

    def __contains__(self, key: str) -> bool:
        return key in self._where and key != GROUND

    def __len__(self) -> int:
        return len(self._where) - 1

    def add(self, body: int, links: int, places: Sequence[Place]) -> None:
        """A new multibody of ``links`` links and the parts it carries. Kinematic mode:
        every link crowded until its neighbourhood is known (:mod:`.contacts`)."""
        for link in range(-1, links):
            self._filter(body, link, crowded=self._dynamics is None)
        keys_of = self._keys_of[body] = [None] * (links + 1)
        for key, link, geometry in places:
            self._where[key] = (body, link)
            keys_of[link] = key
            self._padding[key] = 0.0 if geometry["kind"] in ("sphere", "box") else CONVEX_MARGIN

    def remove(self, body: int, keys: Sequence[str]) -> None:
        """A multibody taken out, with the parts of ``keys`` it carried."""
        for key in keys:
            del self._where[key], self._padding[key]
        del self._keys_of[body]
        self._named.clear()  # (Bullet gives a removed body's id to the next one made)
        # ... and with it, its contacts of the last step
        self._points = [p for p in self._points if body not in (p[1], p[2])]

    def _filter(self, body: int, link: int, crowded: bool = False) -> None:
        group, mask = (CROWD_GROUP, CROWD_MASK) if crowded else (BODY_GROUP, BODY_MASK)
        pybullet.setCollisionFilterGroupMask(body, link, group, mask, physicsClientId=self._client)

    def crowd(self, key: str, crowded: bool) -> None:
        """Let Bullet pair the part ``key`` with the ground and other parts, or (in a crowd)
        with nothing; in dynamic mode everything meets everything (it must not fall through)."""
        if self._dynamics is None:
            self._filter(*self._where[key], crowded=crowded)

    # --- poses and boxes -----------------------------------------------------------------

    def pose(self, key: str) -> Pose:
        """The world pose PyBullet holds for the part ``key``."""
        body, link = self._where[key]
        if link < 0:
            position, orientation = pybullet.getBasePositionAndOrientation(
                body, physicsClientId=self._client)
        else:  # as Bullet's last change left the link (each ends in forward kinematics)
            position, orientation = pybullet.getLinkState(body, link, physicsClientId=self._client)[:2]
        return tuple(position), tuple(orientation)

    def aabb(self, key: str) -> tuple[Vec3, Vec3]:
        """The world box around the part ``key`` (its shape's margin included)."""
        body, link = self._where[key]
        low, high = pybullet.getAABB(body, link, physicsClientId=self._client)
        return tuple(low), tuple(high)

    def aabbs(self, keys: list[str]) -> list[tuple[Vec3, Vec3]]:
        """The world boxes of the parts of ``keys`` (as :meth:`aabb`), in order."""
        get, where, client = pybullet.getAABB, self._where, self._client
        return [get(*where[key], physicsClientId=client) for key in keys]

    # --- contacts ------------------------------------------------------------------------

    @property
    def detects_afresh(self) -> bool:
        """True when each :meth:`detect` runs Bullet's narrowphase once (kinematic mode), so
        that a pair it did not report at the detect before has only points measured now;
        in dynamic mode the steps between two detects ran it several times."""
        return self._dynamics is None

    def detect(self) -> dict[tuple[str, str], float]:
        """Bullet's own collision detection over the parts it pairs (all but those in a
        crowd) and the ground: for each pair with contact points, by how much its nearest
        point misses touching (≤ 0: touching, by the measure of :meth:`touching`)."""
        client = self._client
        if self._dynamics is None:  # (dynamic mode: its last step detected them)
            pybullet.performCollisionDetection(physicsClientId=client)
        found: dict[tuple[str, str], float] = {}
        nearest, inf, named, name = found.get, math.inf, self._named.get, self._name
        points = pybullet.getContactPoints(physicsClientId=client)
        if self._dynamics is not None:
            self.forces = forces_by_part(points, self._keys_of, self._dynamics.units.force)
            self._points = points
        if len(self._named) > NAMED_POINTS:
            self._named.clear()
        for point in points:
            where = point[1:5]  # (body a, body b, link a, link b)
            pair, reach = named(where) or name(where)
            excess = point[8] - reach
            if excess < nearest(pair, inf):
                found[pair] = excess
        return found

    def _name(self, where: tuple[int, int, int, int]) -> tuple[tuple[str, str], float]:
        """The parts of a contact point's bodies and links, as a pair, and its reach: kept
        for the point's next ticks (a tick's 160 points looked up, not worked out)."""
        keys_of = self._keys_of
        a, b = keys_of[where[0]][where[2]], keys_of[where[1]][where[3]]
        pair = (a, b) if a < b else (b, a)  # type: ignore[operator]
        self._named[where] = named = pair, self._reach(a, b)  # type: ignore[arg-type,assignment]
        return named  # type: ignore[return-value]

    def _reach(self, a: str, b: str) -> float:
        """How far apart the points of two parts may be and still touch: the tolerance,
        less what pads each shape (the same either way round)."""
        return TOUCH_TOLERANCE - (self._padding[a] + self._padding[b])

    def contacts(self, keys: Collection[str]) -> dict[str, tuple[ContactForce, ...]]:
        """Dynamic mode: what presses on each part of ``keys`` at the last step, body by
        body (parts nothing presses on are left out; kinematic mode: none)."""
        if self._dynamics is None or not self._points:
            return {}
        return contacts_by_part(self._points, self._keys_of, keys, self._dynamics.units.force)

    def touching(self, key_a: str, key_b: str) -> bool:
        """True when the exact shapes of two parts (or a part and the ground) touch.

        Convex shapes are padded by ``CONVEX_MARGIN``, which the distance is measured against.
        """
        return self.touching_many(key_a, [key_b])[0]

    def touching_many(self, key: str, others: list[str]) -> list[bool]:
        """For each of ``others``: does it touch ``key`` (as :meth:`touching`)?"""
        closest, client = pybullet.getClosestPoints, self._client
        where, tolerance = self._where, TOUCH_TOLERANCE
        a, link_a = where[key]
        out = []
        for other in others:
            b, link_b = where[other]
            reach = self._reach(key, other)
            out.append(any(point[8] <= reach for point in closest(
                a, b, tolerance, link_a, link_b, physicsClientId=client)))
        return out
