"""Every message between the server and a scene's process arrives whole through a real
pipe, in a process that imported nothing of ours before: the class, its fields, errors
with their details and functions by name."""

from __future__ import annotations

import dataclasses
import multiprocessing
import pickle
from typing import Any

from server.core.kit.errors import UnknownObject, UnknownScene, VPError
from server.core.scene.scene import Scene
from server.web.connections.outgoing import Outgoing
from server.web.process import messages
from server.web.process.messages import (Admit, Answers, Ask, Detach, Detached, Ended, Frame,
                                         Idle, Import, Join, Leave, Metrics, Place,
                                         ProcessMessage, Read, Ready, Record, Recorded,
                                         RecordingStarted, Reply, Saving, Stop, Text, Unrecord)
from tests.conftest import WAIT_SECONDS

HELLO = Outgoing.of({"op": "hello", "client": "c7", "tickRate": 60})
FRAME = Outgoing.of({"op": "frame", "seq": 3, "time": 0.05, "angles": {"c7.m": 0.25}})

SAMPLES: list[ProcessMessage] = [
    Join(7, "c7", "controller", "c7:key", True, False),
    Join(("g1-2", 7), "c7", "viewer"),  # a cluster's worker names a connection so
    Text(7, '{"op": "create", "object": "c7.b", "type": "Box", "id": 1}'),
    Text(7, b'{"op": "batch", "ops": []}'),
    Leave(7),
    Ask(1, Read(Scene.snapshot)),
    Ask(2, Read(Scene.get, ("c7.b",))),
    Ask(3, Import(b'{"nodes": []}', True)),
    Ask(4, Place("hand.urdf", (0.0, 0.1, 0.0), (0.0, 0.0, 0.0, 1.0))),
    Ask(5, Metrics()),
    Ask(6, Record("r1", "/tmp/recordings/r1.mcap")),
    Ask(7, Unrecord("r1")),
    Stop(),
    Detach(),
    Admit(7, [HELLO, FRAME]),
    Answers(("g1-2", 7), [FRAME], 57),
    Reply(1, True, b'{"nodes": []}'),
    Reply(2, False, UnknownObject("no object c7.nope", object="c7.nope")),
    Reply(5, True, {"ticks": 12, "tickMs": {"p50": 1.5}}),
    Ready(["demo", "c7"]),
    Frame([FRAME]),
    Idle(),
    Saving({"saved": False, "atRisk": True}),
    RecordingStarted("r1"),
    Recorded({"id": "r1", "messages": 120, "stopped": "stopped"}),
    Ended(False),
    Ended(True, UnknownScene("no worker took scene lab", scene="lab")),
    Detached(),
]


def message_classes(module: Any) -> set[type]:
    return {value for value in vars(module).values() if isinstance(value, type)
            and issubclass(value, ProcessMessage) and value is not ProcessMessage
            and value.__module__ == module.__name__}


def same(sent: Any, received: Any) -> bool:
    """Equal as a reader sees them: messages field by field, a message to a client by its
    op and text, an error by its wire form."""
    if type(sent) is not type(received):
        return False
    if isinstance(sent, ProcessMessage):
        return all(same(getattr(sent, f.name), getattr(received, f.name))
                   for f in dataclasses.fields(sent))  # type: ignore[arg-type]
    if isinstance(sent, Outgoing):
        return (sent.op, sent.text) == (received.op, received.text)
    if isinstance(sent, VPError):
        return sent.to_wire() == received.to_wire()
    if isinstance(sent, (list, tuple)):
        return len(sent) == len(received) and all(map(same, sent, received))
    return bool(sent == received)


def echo(pipe: Any) -> None:
    """A fresh process's side: send back what came."""
    pipe.send(pipe.recv())


def test_every_message_has_a_sample():
    """(A new message without one fails here: the round trips below cover every one.)"""
    assert {type(sample) for sample in SAMPLES} | {type(sample.question) for sample in SAMPLES
                                                   if isinstance(sample, Ask)} \
        == message_classes(messages)


def test_every_message_comes_back_whole_through_a_pipe_to_a_fresh_process():
    context = multiprocessing.get_context("spawn")  # (imports ours anew, as pickle names it)
    here, there = context.Pipe()
    process = context.Process(target=echo, args=(there,))
    process.start()
    try:
        here.send(SAMPLES)
        assert here.poll(WAIT_SECONDS), "the process sent nothing back"
        back = here.recv()
    finally:
        process.join(WAIT_SECONDS)
    assert len(back) == len(SAMPLES)
    for sent, received in zip(SAMPLES, back):
        assert same(sent, received), (sent, received)
    assert not same(SAMPLES[0], Join(7, "c7", "controller"))  # (same() tells them apart)


def test_a_message_is_pickled_as_its_values_not_its_fields_names():
    """A flood sends thousands a second: the names would more than double its bytes."""
    data = pickle.dumps(Text(7, "x"))
    assert b"cid" not in data and b"text" not in data
    assert len(pickle.dumps([Text(k, "x") for k in range(100)])) < 100 * 12
