"""The undo journal: an operation, or a whole batch, applies completely or not at all."""

import pytest

from server.core.kit.journal import Journal


def test_a_failed_transaction_undoes_its_changes_newest_first():
    journal, state, undone = Journal(), {"a": 1, "b": 1}, []
    with pytest.raises(ValueError), journal.transaction():
        for key in ("a", "b"):
            old = state[key]
            state[key] = 2
            journal.record(lambda key=key, old=old: (undone.append(key), state.__setitem__(key, old)))
        raise ValueError("refused")
    assert state == {"a": 1, "b": 1} and undone == ["b", "a"]
    assert not journal.active


def test_a_nested_transaction_joins_the_outer_one():
    journal, state = Journal(), []
    with pytest.raises(KeyError), journal.transaction():
        state.append(1)
        journal.record(state.pop)
        with journal.transaction():      # an inner operation that succeeded
            state.append(2)
            journal.record(state.pop)
        raise KeyError("the batch's last operation failed")
    assert state == []


def test_outside_a_transaction_nothing_is_kept_and_a_kept_one_is_forgotten():
    journal, state = Journal(), [1]
    journal.record(state.pop)            # nothing to undo into
    with journal.transaction():
        journal.record(state.pop)
    assert state == [1] and not journal.active
