"""The outbox: order kept, frames folded, a stalled reader cut off."""

import asyncio
import weakref

import pytest

from server.web.connections.outbox import Outbox, SlowConsumer
from server.web.connections.outgoing import Outgoing


def frame(seq, **angles):
    return Outgoing.of({"op": "frame", "seq": seq, "time": seq / 60, "angles": angles})


def test_waiting_frames_fold_but_answers_keep_their_place():
    outbox = Outbox()
    outbox.put(frame(1, a=1.0))
    outbox.put(frame(2, b=2.0))
    outbox.put(Outgoing.of({"op": "ok", "id": 7}))
    outbox.put(frame(3, a=3.0))

    async def drain():
        return [(await outbox.get()).message for _ in range(3)]
    first, answer, last = asyncio.run(drain())
    assert first == {"op": "frame", "seq": 2, "time": 2 / 60, "angles": {"a": 1.0, "b": 2.0}}
    assert answer == {"op": "ok", "id": 7}
    assert last["seq"] == 3 and outbox.merged == 1


def test_a_reader_that_never_reads_is_cut_off_by_bytes_waiting():
    answer = Outgoing.of({"op": "ok", "id": 1, "result": "x" * 1000})
    outbox = Outbox(limit=3 * len(answer.text) + 100)
    for _ in range(3):
        outbox.put(answer)
    outbox.put(frame(1, a=1.0))  # small: still room
    with pytest.raises(SlowConsumer, match="bytes waiting"):
        outbox.put(answer)
    assert asyncio.run(outbox.get()) is answer and outbox.bytes == 2 * len(answer.text) + len(
        frame(1, a=1.0).text)


def test_readers_behind_by_the_same_frames_share_one_fold():
    """A frame reaching 200 slow readers that all have the same frame waiting is folded
    once, and each gets it whole; a reader behind by more frames gets its own fold."""
    outboxes = [Outbox() for _ in range(200)]
    first, second, third = frame(1, a=1.0), frame(2, b=2.0), frame(3, a=3.0)
    for outbox in outboxes:
        outbox.put(first)
        outbox.put(second)
    outboxes[0].put(third)  # this one is a frame further behind

    async def drain(outbox):
        return await outbox.get()
    folds = [asyncio.run(drain(outbox)) for outbox in outboxes]
    assert all(fold is folds[1] for fold in folds[1:])  # one object: merged and encoded once
    assert folds[1].message == {"op": "frame", "seq": 2, "time": 2 / 60,
                                "angles": {"a": 1.0, "b": 2.0}}
    assert folds[0].message == {"op": "frame", "seq": 3, "time": 3 / 60,
                                "angles": {"a": 3.0, "b": 2.0}}
    assert all(outbox.merged == 1 for outbox in outboxes[1:]) and outboxes[0].merged == 2


def test_a_fold_keeps_no_earlier_frame_alive():
    """Two readers that lag in turn (each finds the other's last frame folded into the
    next) do not chain every frame to the one before in memory: a frame read is gone."""
    readers = [Outbox(), Outbox()]
    first = frame(1, a=1.0)
    gone = weakref.ref(first)

    async def drain(outbox):
        while len(outbox):
            await outbox.get()
    for seq in range(1, 50):
        item = first if seq == 1 else frame(seq, a=float(seq))
        for outbox in readers:
            outbox.put(item)
        asyncio.run(drain(readers[seq % 2]))  # one reads, the other lags a frame
    del first, item
    assert gone() is None
    assert asyncio.run(readers[0].get()).message["angles"] == {"a": 49.0}
