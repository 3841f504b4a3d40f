"""The process heap: long-lived objects out of the collector's way."""

from __future__ import annotations

import gc
from collections.abc import Iterator

import pytest

from server.web.process import heap


class Payload:
    """Something made before start-up ended."""


@pytest.fixture
def unfrozen() -> Iterator[None]:
    yield
    gc.unfreeze()


def test_settle_keeps_what_start_up_made_out_of_every_collection(unfrozen: None) -> None:
    before = Payload()
    heap.settle()
    after = Payload()
    walked = {id(o) for o in gc.get_objects()}  # what a full collection walks
    assert id(before) not in walked
    assert id(after) in walked

