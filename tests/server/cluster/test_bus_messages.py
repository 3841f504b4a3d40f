"""Every message of the cluster, and every scene's command and event inside them, arrives
whole over a real NATS server."""

from __future__ import annotations

import asyncio
from typing import Any

from server.cluster import bus_messages
from server.cluster.bus import Bus, ReturnAddress
from server.cluster.bus_messages import (Addressed, Attach, Attached, Elsewhere, Full, Load,
                                         NoRoom, SceneCommands, SceneEvents)
from server.web.process.messages import Event
from tests.conftest import WAIT_SECONDS
from tests.server.web.process.test_messages import SAMPLES, message_classes, same

LOAD = Load("w1", 2, None, 812.5)
FULL = Load("w2", 4, NoRoom("workerCores", 2.0, "--worker-cores", "its 4 scenes would use 1.7"),
            813.0)
COMMANDS = [sample for sample in SAMPLES if not isinstance(sample, Event)]
EVENTS = [sample for sample in SAMPLES if isinstance(sample, Event)]
BUS_SAMPLES: list[Any] = [
    Attach("g1-1", "lab", True),
    Attached(4711, "w1.3", ["demo"], {"saved": True}, False, LOAD),
    Attached(None, "w1.4", None, {}, True, LOAD),
    Full(FULL),
    Elsewhere("w2"),
    SceneCommands("g1-1", COMMANDS),
    SceneEvents("w1.3", [Addressed(None if k % 2 else "g1-1", event)
                         for k, event in enumerate(EVENTS)]),
]


def test_every_bus_message_has_a_sample():
    assert {type(sample) for sample in BUS_SAMPLES} | {Addressed} == message_classes(bus_messages)


def test_every_message_comes_back_whole_over_the_bus(bus_url):
    async def round_trips() -> list[Any]:
        bus = await Bus.connect(bus_url, "test", 3.0)
        try:
            async def echo(value: Any, reply: ReturnAddress | None) -> None:
                assert reply is not None
                await reply.send(value)
            await bus.subscribe("vp.test.echo", echo)
            return [await bus.request("vp.test.echo", sample, WAIT_SECONDS)
                    for sample in BUS_SAMPLES]
        finally:
            await bus.close()
    back = asyncio.run(round_trips())
    for sent, received in zip(BUS_SAMPLES, back, strict=True):
        assert same(sent, received), (sent, received)
