"""Which ids a scene has handed out, remembered in bounded memory so that none is reused.

An id a client makes is ``<owner>.<name>`` (``c7.12``, ``c7.arm``); parts made inside
another object get ``<id>/<k>``, so they are new whenever their top id is. Numeric names
are remembered as runs of integers (a client counting up costs one run), other names one
by one, at most ``client_names`` of them per owner. When a client leaves, its entry is
forgotten: client ids are never handed out twice, and nobody else may make ``c7.`` ids.
"""

from __future__ import annotations

from bisect import bisect_right

from typing import Any

from .errors import DuplicateId, LimitExceeded
from .journal import Journal

_MAX_NUMBER_DIGITS = 15  # longer numeric names are remembered as names


def owner_of(node_id: str) -> str:
    """Who made an object: the part of its id before the first dot (``c7`` of ``c7.3/1``)."""
    return node_id.partition(".")[0]


class IntegerRuns:
    """A set of integers stored as sorted, disjoint, non-adjacent [start, end] runs."""

    def __init__(self) -> None:
        self._starts: list[int] = []
        self._ends: list[int] = []

    def __contains__(self, n: int) -> bool:
        k = bisect_right(self._starts, n) - 1
        return k >= 0 and n <= self._ends[k]

    def __len__(self) -> int:
        """The number of runs (the memory this set costs)."""
        return len(self._starts)

    def add(self, n: int) -> None:
        """Add ``n`` (not already present), merging it into its neighbours' runs."""
        k = bisect_right(self._starts, n) - 1
        joins_left = k >= 0 and self._ends[k] == n - 1
        joins_right = k + 1 < len(self._starts) and self._starts[k + 1] == n + 1
        if joins_left and joins_right:
            self._ends[k] = self._ends.pop(k + 1)
            del self._starts[k + 1]
        elif joins_left:
            self._ends[k] = n
        elif joins_right:
            self._starts[k + 1] = n
        else:
            self._starts.insert(k + 1, n)
            self._ends.insert(k + 1, n)

    @classmethod
    def of(cls, runs: list[list[int]]) -> IntegerRuns:
        """The set of the integers in these [start, end] runs (in any order, overlapping or not)."""
        merged = cls()
        for start, end in sorted(runs):
            if merged._ends and start <= merged._ends[-1] + 1:
                merged._ends[-1] = max(merged._ends[-1], end)
            else:
                merged._starts.append(start)
                merged._ends.append(end)
        return merged

    def runs(self) -> list[list[int]]:
        """The runs as [start, end] pairs, lowest first."""
        return [[start, end] for start, end in zip(self._starts, self._ends)]

    def remove(self, n: int) -> None:
        """Take ``n`` (present) out again, splitting its run if needed."""
        k = bisect_right(self._starts, n) - 1
        start, end = self._starts[k], self._ends[k]
        if start == end:
            del self._starts[k], self._ends[k]
        elif n == start:
            self._starts[k] = n + 1
        elif n == end:
            self._ends[k] = n - 1
        else:
            self._ends[k] = n - 1
            self._starts.insert(k + 1, n + 1)
            self._ends.insert(k + 1, end)


class _Owner:
    def __init__(self) -> None:
        self.numbers = IntegerRuns()
        self.names: set[str] = set()

    def reset(self, runs: list[list[int]], names: set[str]) -> None:
        self.numbers = IntegerRuns.of(runs)
        self.names = names


class IdBook:
    """Top-level ids ever made in a scene, per owner (changes are journaled)."""

    def __init__(self, journal: Journal, names_per_owner: int) -> None:
        self._journal = journal
        self._names_per_owner = names_per_owner
        self._owners: dict[str, _Owner] = {}

    def claim(self, object_id: str, scene: str) -> None:
        """Note a new top-level id; :class:`DuplicateId` if it was ever used before."""
        owner_name, _, name = object_id.partition(".")
        owner = self._owners.setdefault(owner_name, _Owner())
        number = _number(name)
        if number is not None:
            if number in owner.numbers:
                raise _reused(object_id, scene)
            owner.numbers.add(number)
            self._journal.record(lambda: owner.numbers.remove(number))
            return
        if name in owner.names:
            raise _reused(object_id, scene)
        if len(owner.names) >= self._names_per_owner:
            raise LimitExceeded(
                f"{owner_name} has used {self._names_per_owner} non-numeric ids in scene "
                f"{scene}; name objects made in a loop {owner_name}.<number>",
                limit="clientNames", value=self._names_per_owner, object=object_id)
        owner.names.add(name)
        self._journal.record(lambda: owner.names.discard(name))

    def used(self, object_id: str) -> bool:
        """True when the top-level id of ``object_id`` was made at some time."""
        owner_name, _, name = object_id.split("/", 1)[0].partition(".")
        owner = self._owners.get(owner_name)
        if owner is None:
            return False
        number = _number(name)
        return number in owner.numbers if number is not None else name in owner.names

    def forget(self, owner_name: str) -> None:
        """Drop what an owner used: it will never make ids again (a client that left)."""
        self._owners.pop(owner_name, None)

    def wire(self) -> dict[str, dict[str, list[Any]]]:
        """Every id used so far, per owner: numeric names as runs, the others sorted."""
        return {name: {"numbers": owner.numbers.runs(), "names": sorted(owner.names)}
                for name, owner in sorted(self._owners.items())}

    def absorb(self, used: dict[str, dict[str, list[Any]]]) -> None:
        """Note ids of :meth:`wire`'s form as used too (a scene restored from a document:
        what its objects were once called stays taken), journaled."""
        for owner_name, entry in used.items():
            if len(entry["names"]) > self._names_per_owner:
                raise LimitExceeded(f"{owner_name} used {len(entry['names'])} non-numeric ids; "
                                    f"a scene keeps at most {self._names_per_owner}",
                                    limit="clientNames", value=self._names_per_owner)
            owner = self._owners.setdefault(owner_name, _Owner())
            numbers, names = owner.numbers.runs(), set(owner.names)
            self._journal.record(lambda o=owner, r=numbers, n=names: o.reset(r, n))
            owner.reset(numbers + entry["numbers"], names | set(entry["names"]))

    def cost(self) -> int:
        """Entries remembered (runs and names): what this book costs in memory."""
        return sum(len(o.numbers) + len(o.names) for o in self._owners.values())


def _number(name: str) -> int | None:
    """The integer a canonical decimal name stands for (``12``; not ``012``)."""
    if name.isdigit() and name.isascii() and len(name) <= _MAX_NUMBER_DIGITS \
            and (name == "0" or name[0] != "0"):
        return int(name)
    return None


def _reused(object_id: str, scene: str) -> DuplicateId:
    return DuplicateId(f"id {object_id} was already used in scene {scene}; ids are never "
                       f"reused", object=object_id)
