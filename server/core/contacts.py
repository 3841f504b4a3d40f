"""Contacts: which pairs of physical parts (and the ground) touch, and how that changes.

A pair is two ids in sorted order; the ground's id is ``"ground"``. The book holds the
pairs announced at the last tick, so clients see every change exactly once, in order.
"""

from __future__ import annotations

from typing import Iterable

Pair = tuple[str, str]


class Overlaps:
    """Pairs touching at one moment, indexed by id."""

    def __init__(self, pairs: Iterable[Pair]) -> None:
        self.pairs = frozenset(pairs)
        partners: dict[str, list[str]] = {}
        for a, b in sorted(self.pairs):
            partners.setdefault(a, []).append(b)
            partners.setdefault(b, []).append(a)
        self._partners = {node_id: sorted(others) for node_id, others in partners.items()}

    def of(self, node_id: str) -> list[str]:
        """What ``node_id`` touches, sorted."""
        return self._partners.get(node_id, [])


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
