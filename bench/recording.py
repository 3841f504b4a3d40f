"""What recording costs: the MCAP file's size per minute and the scene process's time per
tick for animated hands (every motor turning every tick: the most a recording holds)."""

from __future__ import annotations

import io
import time
from typing import Any

from server.core.recording.mcap_recorder import Recorder, RecordingLimits

from . import scenes
from .core import PERIOD, Bench
from .stats import figure


def recording(hands: int, ticks: int) -> dict[str, Any]:
    """Record ``ticks`` ticks of hands-``hands`` flexing: bytes a minute, ms a tick."""
    bench = Bench(scenes.hands("c1", hands))
    bench.scene.tick(PERIOD)
    stream = io.BytesIO()
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
    size = len(stream.getvalue())
    return {"hands": hands, "ticks": ticks, "bytes": size,
            "mb_per_minute": size / (ticks * PERIOD) * 60 / 1e6, "record_ms": figure(spent)}
