"""Watches: who watches which sensor, journaled, capped."""

import pytest

from server.core.kit.journal import Journal
from server.core.model.watches import Watches
from server.core.kit.errors import LimitExceeded


def test_a_sensor_stays_watched_while_anyone_watches_it():
    watches = Watches(Journal(), 10)
    watches.add("s1", "c1")
    watches.add("s1", "c2")
    watches.add("s2", "c1")
    watches.drop_watcher("c1")
    assert watches.ids() == ["s1"]
    watches.remove("s1", "c2")
    assert len(watches) == 0


def test_the_cap_counts_sensors_not_watchers():
    watches = Watches(Journal(), 2)
    for watcher in ("c1", "c2", "c3"):
        watches.add("s1", watcher)
        watches.add("s2", watcher)
    with pytest.raises(LimitExceeded) as caught:
        watches.add("s3", "c1")
    assert caught.value.details == {"limit": 2, "object": "s3"}


def test_a_failed_transaction_watches_nothing():
    journal = Journal()
    watches = Watches(journal, 10)
    watches.add("kept", "c1")
    with pytest.raises(RuntimeError), journal.transaction():
        watches.add("s1", "c1")
        watches.remove("kept", "c1")
        raise RuntimeError("later step failed")
    assert watches.ids() == ["kept"]


def test_forget_drops_deleted_sensors():
    watches = Watches(Journal(), 10)
    watches.add("s1", "c1")
    watches.add("s2", "laser")
    watches.forget(["s1"])
    assert watches.ids() == ["s2"]
