"""A change set notes which nodes changed and how, not the values."""

from server.core.scene.changes import ChangeSet


def test_a_change_set_is_empty_until_something_changes_and_warnings_do_not_count():
    changes = ChangeSet()
    changes.warnings.append("slot 3 of p is not there: attached to p itself")
    assert not changes
    changes.update("n", "name")
    changes.update("n", "children")
    assert changes and changes.updates == {"n": {"name", "children"}}


def test_clearing_forgets_everything():
    changes = ChangeSet()
    changes.born["a"] = None
    changes.scene.add("camera")
    assert changes
    changes.clear()
    assert not changes and changes.born == {} and not changes.scene
