"""Tick cost and request throughput of the sans-I/O core (no sockets): `make bench`.

Ten edged hands (200 motors, 160 convex bodies) flexing every tick, as the DESIGN's
measured floor describes; then a stream of setAngles requests through a session.
"""

from __future__ import annotations

import json
import math
import statistics
import time

from server.core.messages import encode
from server.core.scene import Scene
from server.core.session import Session

HANDS = 10
TICKS = 600


def bench_ticks() -> dict[str, float]:
    scene = Scene("bench")
    session = Session(scene, "c1")
    for i in range(HANDS):
        session.receive(json.dumps([
            {"op": "create", "object": f"c1.{i}", "type": "EdgedHand", "args": [i % 2 == 0]},
            {"op": "call", "object": f"c1.{i}", "method": "setPosition", "args": [i * 2.5, 0, 0]}]))
    scene.tick(1 / 60)
    hands = [scene.nodes[f"c1.{i}"] for i in range(HANDS)]
    apply_ms, tick_ms, sizes = [], [], []
    for n in range(TICKS):
        started = time.perf_counter()
        for hand in hands:
            hand.flex_fingers(0.8 * (0.5 + 0.5 * math.sin(n / 20)))
        applied = time.perf_counter()
        frame = scene.tick(1 / 60)
        text = encode(frame[-1])
        done = time.perf_counter()
        apply_ms.append((applied - started) * 1000)
        tick_ms.append((done - applied) * 1000)
        sizes.append(len(text))
    scene.close()
    return {"hands": HANDS, "bodies": 16 * HANDS, "apply_ms": statistics.mean(apply_ms),
            "tick_ms_mean": statistics.mean(tick_ms),
            "tick_ms_p95": sorted(tick_ms)[int(0.95 * TICKS)],
            "frame_bytes": statistics.mean(sizes)}


def bench_requests(count: int = 5000) -> dict[str, float]:
    scene = Scene("bench")
    session = Session(scene, "c1")
    session.receive(json.dumps({"op": "create", "object": "c1.1", "type": "EdgedHand"}))
    texts = [json.dumps({"op": "call", "id": i, "object": "c1.1", "method": "setAngles",
                         "args": [math.sin(i + k) for k in range(20)]}) for i in range(count)]
    started = time.perf_counter()
    for text in texts:
        session.receive(text)
    elapsed = time.perf_counter() - started
    scene.close()
    return {"requests": count, "per_second": count / elapsed, "us_each": elapsed / count * 1e6}


if __name__ == "__main__":
    print(json.dumps({"ticks": bench_ticks(), "requests": bench_requests()}, indent=1))
