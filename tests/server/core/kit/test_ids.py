"""The id book: ids are never reused, in memory that does not grow with deleted ids."""

import random

import pytest

from server.core.kit.ids import IdBook, IntegerRuns
from server.core.kit.journal import Journal
from server.core.kit.errors import DuplicateId, LimitExceeded


def test_integer_runs_agree_with_a_set_whatever_the_order():
    runs, plain = IntegerRuns(), set()
    numbers = random.Random(4).sample(range(500), 400)
    for n in numbers:
        runs.add(n)
        plain.add(n)
        assert all((k in runs) == (k in plain) for k in range(-1, 502, 7))
    for n in numbers[:200]:
        runs.remove(n)
        plain.discard(n)
    assert all((k in runs) == (k in plain) for k in range(-1, 502))
    counting = IntegerRuns()
    for n in range(1, 10_001):
        counting.add(n)
    assert len(counting) == 1


def test_claims_are_journaled_and_forgotten_per_owner():
    journal = Journal()
    book = IdBook(journal, names_per_owner=2)
    with pytest.raises(ZeroDivisionError), journal.transaction():
        book.claim("c1.5", "s")
        book.claim("c1.arm", "s")
        1 / 0
    assert not book.used("c1.5") and not book.used("c1.arm")
    book.claim("c1.5", "s")
    book.claim("c1.05", "s")  # a name, not the number 5
    assert book.used("c1.5/3") and book.used("c1.05")
    with pytest.raises(DuplicateId):
        book.claim("c1.5", "s")
    book.claim("c1.leg", "s")
    with pytest.raises(LimitExceeded):
        book.claim("c1.hip", "s")
    book.forget("c1")
    assert book.cost() == 0 and not book.used("c1.5")


def test_runs_given_in_any_order_merge_and_a_book_absorbs_them_journaled():
    runs = [[7, 9], [1, 3], [4, 4], [8, 12], [20, 20], [5, 6]]
    assert IntegerRuns.of(runs).runs() == [[1, 12], [20, 20]]
    assert IntegerRuns.of(runs[:4]).runs() == [[1, 4], [7, 12]]
    journal = Journal()
    book = IdBook(journal, 10)
    book.claim("c1.5", "s")
    with pytest.raises(RuntimeError), journal.transaction():
        book.absorb({"c1": {"numbers": [[1, 3]], "names": ["arm"]}, "c2": {"numbers": [], "names": []}})
        assert book.used("c1.2") and book.used("c1.arm")
        raise RuntimeError("the import fails later")
    assert book.wire() == {"c1": {"numbers": [[5, 5]], "names": []}, "c2": {"numbers": [], "names": []}}
    book.absorb({"c1": {"numbers": [[1, 3]], "names": ["arm"]}})
    assert book.wire()["c1"] == {"numbers": [[1, 3], [5, 5]], "names": ["arm"]}
    with pytest.raises(DuplicateId):
        book.claim("c1.arm", "s")
