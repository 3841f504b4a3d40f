"""What recording costs and how fast a player seeks: the MCAP file's size per minute and
the scene process's time per tick for animated hands (every motor turning every tick: the
most a recording holds), then seeks to random times of that file."""

from __future__ import annotations

import random
import tempfile
import time
from typing import Any

from server.core.recording.mcap_recorder import Recorder, RecordingLimits
from server.core.recording.replay import Replay

from . import scenes
from .core import PERIOD, Bench
from .stats import figure


def recording(hands: int, ticks: int, seeks: int) -> dict[str, Any]:
    """Record ``ticks`` ticks of hands-``hands`` flexing into a file: bytes a minute, ms a
    tick; then ``seeks`` seeks to random times of it (ms each, the file opened once)."""
    bench = Bench(scenes.hands("c1", hands))
    bench.scene.tick(PERIOD)
    with tempfile.TemporaryFile() as stream:
        recorder = Recorder(stream, bench.scene, time.time_ns(), RecordingLimits(1 << 40, 1 << 30))
        spent = []
        for n in range(ticks):
            bench.send(scenes.hand_step("c1", hands, n))
            messages = bench.scene.tick(PERIOD)
            started = time.perf_counter()
            recorder.tick(messages, bench.scene)
            spent.append((time.perf_counter() - started) * 1000)
        recorder.finish("stopped", bench.scene)
        bench.close()
        size = stream.tell()
        replay = Replay(stream)
        draw = random.Random(1)
        seeking = []
        for _ in range(seeks):
            started = time.perf_counter()
            replay.at(draw.uniform(0, replay.duration))
            seeking.append((time.perf_counter() - started) * 1000)
    return {"hands": hands, "ticks": ticks, "bytes": size, "minutes": ticks * PERIOD / 60,
            "mb_per_minute": size / (ticks * PERIOD) * 60 / 1e6, "record_ms": figure(spent),
            "seek_ms": figure(seeking), "seek_max_ms": max(seeking)}
