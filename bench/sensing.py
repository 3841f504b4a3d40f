"""Cost of sensing and contacts in the tick (no sockets): part of `make bench`.

Ten edged hands flex every tick (so every body moves and contacts are recomputed each
tick) with 0, 100 or 1000 watched sensors on their fingertips; each frame carries every
watched sensor's readings.
"""

from __future__ import annotations

import json
import math
import statistics
import time

from server.core.hands import EdgedHand
from server.core.messages import encode
from server.core.scene import Scene
from server.core.sensor import Sensor

HANDS = 10
TICKS = 300


def build(sensors: int) -> tuple[Scene, list[EdgedHand]]:
    scene = Scene("bench")
    hands = []
    for i in range(HANDS):
        hand = EdgedHand(scene, f"h{i}", i % 2 == 0)
        hand.set_position((i * 2.5, 0.5, 0))
        hands.append(hand)
    tips = [part for hand in hands for part in hand.get_parts() if part.type_name == "EdgedTip"]
    for k in range(sensors):
        sensor = Sensor(scene, f"s{k}")
        sensor.attach_to_slot(tips[k % len(tips)])
        sensor.set_rotation(0.1 * (k // len(tips)), 0, 0)
        sensor.watch(client="bench")
    scene.tick(1 / 60)
    return scene, hands


def bench(sensors: int) -> dict[str, float]:
    scene, hands = build(sensors)
    tick_ms, contacts_ms, sensing_ms, sizes = [], [], [], []
    for n in range(TICKS):
        for hand in hands:
            hand.flex_fingers(0.4 + 0.8 * (0.5 + 0.5 * math.sin(n / 20)))
        started = time.perf_counter()
        scene.bodies.sync()
        placed = time.perf_counter()
        scene.bodies.overlaps()
        touched = time.perf_counter()
        scene.watched_readings()
        sensed = time.perf_counter()
        frame = scene.tick(1 / 60)  # places nothing new; contacts cached; senses again
        text = encode(frame[-1])
        done = time.perf_counter()
        contacts_ms.append((touched - placed) * 1000)
        sensing_ms.append((sensed - touched) * 1000)
        tick_ms.append((done - sensed) * 1000 + (placed - started) * 1000)
        sizes.append(len(text))
    contacts = len(scene.bodies.contacts.current.pairs)
    scene.close()
    return {"sensors": sensors, "contacts_now": contacts,
            "contacts_ms": statistics.mean(contacts_ms),
            "sensing_ms": statistics.mean(sensing_ms),
            "sensing_ms_p95": sorted(sensing_ms)[int(0.95 * TICKS)],
            "tick_ms": statistics.mean(tick_ms), "frame_bytes": statistics.mean(sizes)}


if __name__ == "__main__":
    print(json.dumps([bench(n) for n in (0, 100, 1000)], indent=1))
