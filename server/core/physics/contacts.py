"""Contacts: which pairs of physical parts (and the ground) touch, and how that changes.

A pair is two ids in sorted order; the ground's id is ``"ground"``. The
:class:`ContactTracker` keeps the touching pairs up to date as bodies move, two ways:

- Bullet's own pair processing (``performCollisionDetection``, then the contact points)
  measures every pair of parts it pairs, in C++, each tick;
- a part in a crowd (and a part just made, until its neighbourhood is known) is left out
  of Bullet's pairing (collision filters): its pairs, the ground's included, are measured one by
  one (``getClosestPoints``), only with parts whose boxes overlap its box, at most
  ``contact_tests`` a tick; parts beyond that wait for the next tick (frames say how many
  under ``limited``). A part with more than ``CROWD`` neighbours stays in the crowd, so a
  pile of boxes never grows Bullet's pair cache with its square; one with fewer than half
  that many goes back to Bullet. While there is a crowd, any part that moves has its pairs
  with crowded parts measured so too (Bullet pairs no crowded part).

A pair that begins touching is confirmed by the exact measure before it counts, unless
every point Bullet has of it was measured by this update's own pass (a pair it did not have
at the update before, in a world that runs Bullet's narrowphase once an update): Bullet
keeps a pair's points from pass to pass and only moves them with the bodies, so an old
point can say two parts touch that have moved apart, while a point measured now is the
exact measure's own (the same algorithm on the same shapes). The :class:`ContactBook` holds
the pairs announced at the last tick, so clients see every change exactly once, in order.
"""

from __future__ import annotations

from itertools import islice
from typing import Iterable, Protocol, Sequence

import numpy as np

from ..kit.math3d import Vec3
from .bullet_parts import GROUND, TOUCH_TOLERANCE

Pair = tuple[str, str]
_BLOCK = 1024  # bodies whose candidates are found in one array operation (bounds memory)
CROWD = 16  # more neighbours than this: a part's pairs are measured one by one


class Bodies(Protocol):
    """What the tracker needs of the physics world."""

    def aabbs(self, keys: list[str]) -> list[tuple[Vec3, Vec3]]: ...

    def touching_many(self, key: str, others: list[str]) -> list[bool]: ...

    def detect(self) -> dict[Pair, float]: ...

    @property
    def detects_afresh(self) -> bool: ...

    def crowd(self, key: str, crowded: bool) -> None: ...


def pair(a: str, b: str) -> Pair:
    """Two ids as a pair (sorted)."""
    return (a, b) if a < b else (b, a)


class Overlaps:
    """Pairs touching at one moment, indexed by id (the index made when first asked)."""

    def __init__(self, pairs: Iterable[Pair]) -> None:
        self.pairs = frozenset(pairs)
        self._partners: dict[str, list[str]] | None = None

    def of(self, node_id: str) -> list[str]:
        """What ``node_id`` touches, sorted."""
        return self.partners.get(node_id, [])

    def partners_of(self, node_ids: Iterable[str | None]) -> list[tuple[str, ...]]:
        """What each of ``node_ids`` touches, sorted (None touches nothing). A tick's
        sensors ask for a few parts: the pairs are gone through once for those alone (for
        ten hands' hundred pairs and fifty parts asked, 21 µs against the whole index's 30)."""
        ids = list(node_ids)
        if self._partners is not None:
            return [tuple(self._partners.get(i, ())) if i is not None else () for i in ids]
        wanted: dict[str | None, list[str]] = {i: [] for i in dict.fromkeys(ids)}  # (parts asked twice)
        for a, b in self.pairs:
            if a in wanted:
                wanted[a].append(b)
            if b in wanted:
                wanted[b].append(a)
        found = {i: tuple(sorted(others)) for i, others in wanted.items()}
        return [found[i] for i in ids]

    @property
    def partners(self) -> dict[str, list[str]]:
        """What each id that touches anything touches, sorted."""
        if self._partners is None:
            partners: dict[str, list[str]] = {}
            for a, b in self.pairs:
                partners.setdefault(a, []).append(b)
                partners.setdefault(b, []).append(a)
            self._partners = {node_id: sorted(others) for node_id, others in partners.items()}
        return self._partners


class ContactTracker:
    """The touching pairs, kept current within a budget of pair tests per update."""

    def __init__(self, bodies: Bodies, tests_per_update: int, max_pairs: int) -> None:
        self._bodies = bodies
        self._budget = tests_per_update
        self._per_key = 8  # candidates of a body, as last found (how many bodies to look at)
        self._max_pairs = max_pairs
        self._rows: dict[str, int] = {}
        self._keys: list[str] = []
        self._low = np.empty((0, 3))
        self._high = np.empty((0, 3))
        self._partners: dict[str, set[str]] = {}
        self._pairs: set[Pair] = set()  # the same pairs, as sorted tuples
        self._found: dict[Pair, float] = {}  # what Bullet had at the last update
        self._near: dict[str, int] | None = None  # each part's pairs in it, the ground's aside
        # moved bodies measured one by one, in the order they moved: crowded ones, and any
        # while there is a crowd (their pairs with it: Bullet pairs no crowded part)
        self._dirty: dict[str, None] = {}
        self._crowded: set[str] = set()  # measured one by one (Bodies.crowd)
        self._stale: dict[str, None] = {}  # bodies whose boxes moved since last read
        self._stale_groups: dict[tuple[str, ...], None] = {}  # the same, a tree's parts at once
        self.unrecorded = 0  # touching pairs left out at the last update (max_pairs)
        self.tests = 0       # pair tests of the last update
        self.updates = 0     # updates run (a world where nothing moved needs none)
        self._snapshot: Overlaps | None = Overlaps(())
        self.crowding = True  # dynamic mode: off (Bullet pairs everything: nothing may fall through)
        self._recrowded = False  # the last update changed the crowd

    # --- bodies --------------------------------------------------------------------------

    def placed(self, keys: Sequence[str], made: bool = False) -> None:
        """Bodies were added or moved (``made``: their bodies were made afresh, as every
        new body is): their contacts must be measured again. A body made afresh starts in
        the crowd, until its neighbourhood is measured."""
        new = [key for key in keys if key not in self._rows]
        for key in new:
            self._rows[key] = len(self._keys)
            self._keys.append(key)
        if new:
            grown = np.zeros((len(new), 3))
            self._low, self._high = np.vstack([self._low, grown]), np.vstack([self._high, grown])
        self._stale.update(dict.fromkeys(keys))
        if self.crowding:
            self._crowded.update(keys if made else new)
        if self._crowded:  # (a part moved to a crowd meets it only through its own measures)
            self._dirty.update(dict.fromkeys(keys))

    def moved(self, keys: tuple[str, ...]) -> None:
        """Bodies placed before moved again (a tree's parts): as :meth:`placed`, in a time
        that does not grow with the tree while nothing is crowded (a tick moves every tree)."""
        self._stale_groups[keys] = None
        if len(self._stale_groups) > _BLOCK:  # (bounded while nothing reads the boxes)
            self._ungroup_stale()
        if self._crowded:  # its pairs with crowded parts are measured one by one (_measure)
            self._dirty.update(dict.fromkeys(keys))

    def made_again(self) -> None:
        """Every body was made afresh (a new physics client): all start in the crowd (none
        without crowding)."""
        if not self.crowding:
            self._crowded.clear()
        self.placed(list(self._keys), made=True)

    def _ungroup_stale(self) -> None:
        rows = self._rows  # (a body since removed is left out)
        self._stale.update(dict.fromkeys(k for group in self._stale_groups for k in group
                                         if k in rows))
        self._stale_groups.clear()

    def _read_boxes(self) -> None:
        """Read the boxes of the bodies that moved since they were last read."""
        self._ungroup_stale()
        if self._stale:
            keys = list(self._stale)
            boxes = np.array(self._bodies.aabbs(keys), dtype=float).reshape(len(keys), 2, 3)
            rows = [self._rows[key] for key in keys]
            self._low[rows], self._high[rows] = boxes[:, 0], boxes[:, 1]
            self._stale.clear()

    def removed(self, key: str) -> None:
        """A body left the world: its pairs end now (nothing for a body never placed)."""
        row = self._rows.pop(key, None)
        if row is None:
            return
        last = len(self._keys) - 1
        if row != last:  # the last row takes the freed place
            moved = self._keys[last]
            self._keys[row], self._rows[moved] = moved, row
            self._low[row], self._high[row] = self._low[last], self._high[last]
        self._keys.pop()
        self._low, self._high = self._low[:last], self._high[:last]
        for other in list(self._partners.get(key, ())):
            self._set(key, other, False)
        self._dirty.pop(key, None)
        self._stale.pop(key, None)
        self._crowded.discard(key)

    # --- measuring -----------------------------------------------------------------------

    @property
    def deferred(self) -> int:
        """Moved bodies whose contacts are not measured yet."""
        return len(self._dirty)

    def update(self) -> None:
        """Measure what Bullet pairs, then the pairs of moved crowded bodies, in the order
        they moved, within the budget."""
        self.tests = self.unrecorded = 0
        self.updates += 1
        self._recrowded = False
        self._from_bullet()
        if not self._dirty:
            return
        self._read_boxes()
        while self._dirty and (self.tests == 0 or self.tests < self._budget):
            # as many bodies as the budget left may measure, by the last count of their
            # candidates (1 800 balls in one spot: 1 024 bodies' candidates a tick, 1.8 M
            # pairs, for the one or two the budget measured, 0.4 s a tick)
            block = (self._budget - self.tests) // max(1, self._per_key) + 1
            keys = list(islice(self._dirty, min(_BLOCK, block)))
            found = self._candidates(keys)
            self._per_key = max(1, round(sum(map(len, found)) / len(found)))
            for key, candidates in zip(keys, found):
                if key not in self._crowded:  # its pairs with crowded parts (Bullet: the rest)
                    candidates = [c for c in candidates if c in self._crowded]
                waiting = [c for c in candidates if c in self._dirty and c != key]
                tests = len(candidates) - len(waiting)
                if self.tests and self.tests + tests > self._budget:
                    return
                del self._dirty[key]
                self._measure(key, candidates, skip=set(waiting))

    def _from_bullet(self) -> None:
        """Take Bullet's pairs: those no longer found touching end, those found touching
        begin (confirmed by the exact measure unless Bullet's points of them are all new);
        parts with too many neighbours join the crowd. Set operations, not a loop over
        every pair: most pairs stay as they were."""
        found, crowded, rows = self._bodies.detect(), self._crowded, self._rows
        # a pair Bullet did not have before has only points measured by this pass (in
        # hands-10, two thirds of the pairs that begin: a getClosestPoints each saved)
        afresh, before, self._found = self._bodies.detects_afresh, self._found, found
        touching = {p for p, excess in found.items() if excess <= 0.0}
        for a, b in self._pairs - touching:
            if a not in crowded and b not in crowded:  # Bullet measures it, and found it apart
                self._set(a, b, False)
        for a, b in sorted(touching - self._pairs):  # sorted: the same pairs kept at the limit
            if (a in rows or a == GROUND) and (b in rows or b == GROUND):  # not a body gone
                if afresh and (a, b) not in before:
                    self._set(a, b, True)
                else:  # its points may be old ones, moved with the bodies: measured again
                    self.tests += 1
                    self._set(a, b, self._bodies.touching_many(a, [b])[0])
        if not self.crowding:
            self._near = None
            return
        for key in self._count_neighbours(found, before):
            if key not in crowded and key in rows:
                self._crowd(key, True)
                self._dirty[key] = None

    def _count_neighbours(self, found: dict[Pair, float], before: dict[Pair, float]) -> list[str]:
        """Bring each part's count of the parts Bullet pairs it with (the ground aside) up
        to ``found``; the parts that gained one and have more than CROWD. Only the pairs
        Bullet found or lost since the update before change a count: two differences of
        dicts' keys, whose hashes the dicts keep, instead of counting every pair's parts
        again (hands-10's 160 pairs: 10 us against 18)."""
        near = self._near
        if near is None:  # (the first update, or crowding again after dynamic mode)
            near = self._near = {}
            gained, lost = found.keys(), ()
        else:
            gained, lost = found.keys() - before.keys(), before.keys() - found.keys()
        for a, b in lost:
            if a != GROUND and b != GROUND:
                for key in (a, b):
                    near[key] -= 1
                    if not near[key]:
                        del near[key]
        over = []
        for a, b in gained:
            if a != GROUND and b != GROUND:
                for key in (a, b):
                    near[key] = count = near.get(key, 0) + 1
                    if count > CROWD:
                        over.append(key)
        return over

    def _crowd(self, key: str, crowded: bool) -> None:
        (self._crowded.add if crowded else self._crowded.discard)(key)
        self._bodies.crowd(key, crowded)
        self._recrowded = True

    @property
    def unsettled(self) -> bool:
        """Another update may find what this one did not, though nothing moved: moved
        bodies were left for it (the budget), or the crowd changed (Bullet then pairs
        other bodies)."""
        return bool(self._dirty) or self._recrowded

    def settle(self, key: str) -> None:
        """Measure every pair of one body now (an exact read of its contacts)."""
        if key in self._rows:
            self._read_boxes()
            [candidates] = self._candidates([key])
            self._dirty.pop(key, None)
            self._measure(key, candidates, skip=set(), every=True)

    def _measure(self, key: str, candidates: list[str], skip: set[str],
                 every: bool = False) -> None:
        """Measure ``key``'s pairs with ``candidates`` and end those with parts no longer
        near: all of them for a crowded part (or ``every``), for another only those with
        crowded parts (Bullet measures the rest)."""
        crowded = self._crowded
        alone = key not in crowded and not every
        if key in crowded and len(candidates) * 2 < CROWD:  # few neighbours: to Bullet
            self._crowd(key, False)
        near = set(candidates)
        for other in list(self._partners.get(key, ())):
            if other not in near and other not in skip and (not alone or other in crowded):
                self._set(key, other, False)
        tested = [other for other in candidates if other not in skip] if skip else candidates
        self.tests += len(tested)
        for other, touching in zip(tested, self._bodies.touching_many(key, tested)):
            self._set(key, other, touching)

    def _candidates(self, keys: list[str]) -> list[list[str]]:
        """For each body, the bodies whose boxes overlap its box, and the ground if near."""
        rows = np.array([self._rows[k] for k in keys])
        mine, others = self._sweep(rows)
        cut = np.searchsorted(mine, np.arange(len(rows) + 1))
        names = [self._keys[j] for j in others.tolist()]
        found = [names[cut[i]:cut[i + 1]] for i in range(len(rows))]
        for i, bottom in enumerate(self._low[rows, 1].tolist()):
            if bottom <= TOUCH_TOLERANCE:
                found[i].append(GROUND)
        return found

    def _sweep(self, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pairs (index into ``rows``, row) of overlapping boxes, sorted by both.

        Sweep and prune: along the axis where it leaves the fewest, only the bodies whose
        lower edge lies within reach are compared on all three axes.
        """
        low, high, tolerance = self._low, self._high, TOUCH_TOLERANCE
        ranges = [self._ranges(rows, axis) for axis in range(3)]
        order, first, counts = min(ranges, key=lambda r: int(r[2].sum()))
        mine = np.repeat(np.arange(len(rows)), counts)
        offsets = np.arange(len(mine)) - np.repeat(np.cumsum(counts) - counts - first, counts)
        others = order[offsets]
        a, b = rows[mine], others
        apart = (low[b] > high[a] + tolerance) | (high[b] < low[a] - tolerance)
        keep = (a != b) & ~(apart[:, 0] | apart[:, 1] | apart[:, 2])
        mine, others = mine[keep], others[keep]
        order = np.lexsort((others, mine))
        return mine[order], others[order]

    def _ranges(self, rows: np.ndarray, axis: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Along one axis: the rows by lower edge, and per row of ``rows`` the first and the
        number of those whose box may overlap its box (lower edge within the widest box)."""
        low, high = self._low[:, axis], self._high[:, axis]
        order = np.argsort(low, kind="stable")
        starts = low[order]
        reach = float((high - low).max()) + TOUCH_TOLERANCE
        first = np.searchsorted(starts, low[rows] - reach, "left")
        last = np.searchsorted(starts, high[rows] + TOUCH_TOLERANCE, "right")
        return order, first, last - first

    def _set(self, a: str, b: str, touching: bool) -> None:
        partners = self._partners
        if touching == (b in partners.get(a, ())):
            return
        if touching:
            if len(self._pairs) >= self._max_pairs:
                self.unrecorded += 1
                return
            partners.setdefault(a, set()).add(b)
            partners.setdefault(b, set()).add(a)
            self._pairs.add(pair(a, b))
        else:
            for x, y in ((a, b), (b, a)):
                partners[x].discard(y)
                if not partners[x]:
                    del partners[x]
            self._pairs.discard(pair(a, b))
        self._snapshot = None

    def overlaps(self) -> Overlaps:
        """The pairs touching as far as measured."""
        if self._snapshot is None:
            self._snapshot = Overlaps(self._pairs)
        return self._snapshot


class ContactBook:
    """The contacts announced by the last tick."""

    def __init__(self) -> None:
        self.current = Overlaps(())

    def update(self, now: Overlaps) -> tuple[list[Pair], list[Pair]]:
        """Take ``now`` as the current contacts; the pairs that began and ended, sorted."""
        began = sorted(now.pairs - self.current.pairs)
        ended = sorted(self.current.pairs - now.pairs)
        self.current = now
        return began, ended

    def wire(self) -> list[list[str]]:
        """The pairs as they travel: sorted lists of two ids."""
        return [list(pair) for pair in sorted(self.current.pairs)]
