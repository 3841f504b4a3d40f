"""The contact book: pairs diffed into begin and end, indexed by id."""

from server.core.contacts import ContactBook, Overlaps


def test_update_reports_each_change_once():
    book = ContactBook()
    assert book.update(Overlaps([("a", "b"), ("b", "c")])) == ([("a", "b"), ("b", "c")], [])
    assert book.update(Overlaps([("a", "b"), ("b", "c")])) == ([], [])
    assert book.update(Overlaps([("b", "c"), ("a", "ground")])) == ([("a", "ground")],
                                                                    [("a", "b")])
    assert book.current.of("b") == ["c"] and book.current.of("a") == ["ground"]
    assert book.current.of("x") == []
    assert book.wire() == [["a", "ground"], ["b", "c"]]


def test_overlaps_index_both_sides_sorted():
    overlaps = Overlaps([("m", "z"), ("a", "m"), ("ground", "m")])
    assert overlaps.of("m") == ["a", "ground", "z"] and overlaps.of("a") == ["m"]
