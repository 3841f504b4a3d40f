"""The outbox: order kept, frames folded, a stalled reader cut off."""

import asyncio

import pytest

from server.web.outbox import Outbox, Outgoing, SlowConsumer


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
