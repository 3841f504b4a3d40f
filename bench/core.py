"""In-process measures (no sockets): the core's tick against bare PyBullet, sensing,
requests, frame size and how many animated hands fit in a 60 Hz tick.

Each scene is built and animated with the protocol operations of :mod:`bench.scenes`
through a :class:`Session`, as a client's messages would be.
"""

from __future__ import annotations

import gc
import json
import math
import time
from typing import Any, Callable

from server.core.model import part_figures
from server.core.physics.geometry import scaled
from server.core.kit.limits import DEFAULT
from server.core.protocol.messages import encode
from server.core.model.node import UNIT_SCALE
from server.core.scene.scene import Scene
from server.core.protocol.scene_document import encode_document, export_scene, import_scene
from server.core.model.sensor import Sensor
from server.core.protocol.session import Session

from . import scenes
from .floor import BareWorld
from .stats import Figure, figure

LIMITS = DEFAULT.with_values(["bytesPerSecond=1000000000",
                              "watchedSensors=100000"])
PERIOD = 1 / 60


class Bench:
    """A scene built and animated through one session."""

    def __init__(self, ops: list[dict[str, Any]]) -> None:
        self.scene = Scene("bench", LIMITS)
        self.session = Session(self.scene, "c1")
        self.send(ops)
        self.scene.tick(PERIOD)
        gc.collect()
        gc.freeze()  # as the server's scene processes do (server.web.process.heap)

    def send(self, ops: list[dict[str, Any]]) -> None:
        """Apply operations as one batch message (the answers must be ok)."""
        [answer] = self.session.receive(json.dumps({"op": "batch", "id": 1, "ops": ops}))
        assert answer["op"] == "ok", answer

    def bodies(self) -> list[Any]:
        """The physical parts that have bodies, in a fixed order."""
        return [node for node in self.scene.nodes.values() if node.id in self.scene.bodies.physics]

    def close(self) -> None:
        self.scene.close()
        gc.unfreeze()


def tick_against_floor(name: str, ops: list[dict[str, Any]],
                       step: Callable[[int], list[dict[str, Any]]], ticks: int,
                       idle: float = 0.0) -> dict[str, Any]:
    """Our tick (with the frame's encoding) and bare PyBullet placing, detecting and reading
    contacts for the same shapes at the same poses; applying each step's operations apart.

    The two alternate tick by tick (after a warm-up of both), so that whatever else the
    machine does at a moment weighs on both alike, and each starts as cold as the other:
    between two of our ticks the step is applied and the floor steps, and the reverse.
    With ``idle`` seconds of sleep before each tick and each floor, both start as a 60 Hz
    server's ticks do, after the rest of a period: on a virtual machine whose idle core
    is given back to its host, back-to-back ticks measure warm caches no server ticks in
    (hands-10: 1.35 ms back to back, 2.24 after 15 ms idle; the floor 1.25 and 2.05)."""
    bench = Bench(ops)
    bodies = bench.bodies()
    world = BareWorld([_collision_geometry(body) for body in bodies],
                      [body.world_pose() for body in bodies])
    apply_ms, tick_ms, floor_ms = [], [], []
    warm_up = max(1, ticks // 10)
    for n in range(warm_up + ticks):
        started = time.perf_counter()
        bench.send(step(n))
        applied = time.perf_counter()
        if idle:
            time.sleep(idle)
        tick_started = time.perf_counter()
        encode(bench.scene.tick(PERIOD)[-1])
        ticked = time.perf_counter()
        poses = [body.world_pose() for body in bodies]
        if idle:
            time.sleep(idle)
        floor_started = time.perf_counter()
        world.step(poses)
        if n >= warm_up:
            apply_ms.append((applied - started) * 1000)
            tick_ms.append((ticked - tick_started) * 1000)
            floor_ms.append((time.perf_counter() - floor_started) * 1000)
    world.close()
    bench.close()
    return {"scene": name, "bodies": len(bodies), "idle_s": idle, "apply_ms": figure(apply_ms),
            "tick_ms": figure(tick_ms), "floor_ms": figure(floor_ms),
            "ratio": figure(tick_ms).median / figure(floor_ms).median}


def _collision_geometry(node: Any) -> dict[str, Any]:
    scale = node.world_scale()
    return node.geometry() if scale == UNIT_SCALE else scaled(node.geometry(), scale)


def sensing(hands: int, sensors: int, ticks: int) -> dict[str, Any]:
    """Watched sensors on the fingertips of hands-``hands`` (every finger moving): the
    sensing step of each tick, and the same rays cast by bare PyBullet in one batch."""
    bench = Bench(scenes.hands("c1", hands))
    scene = bench.scene
    tips = [n for n in scene.nodes.values() if n.type_name == "EdgedTip"]
    for k in range(sensors):
        sensor = Sensor(scene, f"c1.{1_000_000 + k}")  # numbered: names are limited
        sensor.attach_to_slot(tips[k % len(tips)])
        sensor.set_rotation(0.1 * (k // len(tips)), 0, 0)
        sensor.watch(client="c1")
    scene.tick(PERIOD)
    world = BareWorld([_collision_geometry(b) for b in bench.bodies()],
                      [b.world_pose() for b in bench.bodies()])
    ours, floor, sizes = [], [], []
    for n in range(ticks):
        bench.send(scenes.hand_step("c1", hands, n))
        scene.bodies.overlaps()  # contacts first: sensing is measured alone
        started = time.perf_counter()
        readings = scene.watched_readings()
        ours.append((time.perf_counter() - started) * 1000)
        floor.append(_bare_rays(world, scene, bench))
        sizes.append(len(encode(scene.tick(PERIOD)[-1])))
        assert len(readings) == sensors
    world.close()
    bench.close()
    return {"sensors": sensors, "sensing_ms": figure(ours), "floor_ms": figure(floor),
            "ratio": figure(ours).median / max(figure(floor).median, 1e-9),
            "frame_bytes": figure(sizes)}


def _bare_rays(world: BareWorld, scene: Scene, bench: Bench) -> float:
    world.step([b.world_pose() for b in bench.bodies()])
    origins, ends = [], []
    for node_id in scene.watches.ids():
        (x, y, z), (qx, qy, qz, qw) = scene.nodes[node_id].world_pose()
        up = (2 * (qx * qy - qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz + qw * qx))
        origins.append((x, y, z))
        ends.append(tuple(p + part_figures.SENSOR_RANGE * d for p, d in zip((x, y, z), up)))
    started = time.perf_counter()
    world.rays(origins, ends)
    return (time.perf_counter() - started) * 1000


def requests(count: int) -> dict[str, Any]:
    """``setAngles`` of 20 angles through a session, against decoding and encoding the same
    texts with the standard library alone (what any JSON server does at least)."""
    bench = Bench([{"op": "create", "object": "c1.h", "type": "EdgedHand"}])
    texts = [json.dumps({"op": "call", "id": i, "object": "c1.h", "method": "setAngles",
                         "args": [math.sin(i + k) for k in range(20)]}) for i in range(count)]
    receive, now = bench.session.receive_encoded, time.monotonic
    started = time.perf_counter()
    for text in texts:
        receive(text, now())
    ours = count / (time.perf_counter() - started)
    started = time.perf_counter()
    for text in texts:
        json.dumps(json.loads(text))
    bare = count / (time.perf_counter() - started)
    bench.close()
    return {"requests": count, "per_second": ours, "json_only_per_second": bare,
            "ratio": ours / bare}


def frame_bytes(ticks: int) -> dict[str, Any]:
    """Frames of two hands (x = ±2, as the manual's examples place them) whose every motor
    moves every tick."""
    bench = Bench([{"op": "create", "object": "c1.l", "type": "EdgedHand", "args": [True]},
                   {"op": "call", "object": "c1.l", "method": "setPosition", "args": [-2, 0, 0]},
                   {"op": "create", "object": "c1.r", "type": "EdgedHand", "args": [False]},
                   {"op": "call", "object": "c1.r", "method": "setPosition", "args": [2, 0, 0]}])
    sizes = []
    for n in range(ticks):
        bench.send([{"op": "call", "object": hand, "method": "setAngles",
                     "args": [-0.2 + 0.15 * math.sin(n / 10 + k) for k in range(20)]}
                    for hand in ("c1.l", "c1.r")])
        frame = bench.scene.tick(PERIOD)[-1]
        assert [len(angles) for angles in frame["angles"].values()] == [20, 20]  # every motor
        sizes.append(len(encode(frame).encode()))
    bench.close()
    return {"frame_bytes": figure(sizes)}


def documents(hands: int, rounds: int) -> dict[str, Any]:
    """A scene of animated hands as a document: exporting and encoding it (what
    --state-dir does at most once a second, stalling the scene's ticks meanwhile), its
    size, and importing it into an empty scene."""
    bench = Bench(scenes.hands("c1", hands))
    exports, imports = [], []
    for n in range(rounds):
        bench.send(scenes.hand_step("c1", hands, n))
        bench.scene.tick(PERIOD)
        started = time.perf_counter()
        data = encode_document(export_scene(bench.scene, embed_assets=False))
        exports.append((time.perf_counter() - started) * 1000)
    document = json.loads(data)
    for _ in range(max(1, rounds // 10)):
        target = Scene("copy", LIMITS)
        started = time.perf_counter()
        with target.journal.transaction():
            import_scene(target, document)
        imports.append((time.perf_counter() - started) * 1000)
        target.close()
    bench.close()
    return {"hands": hands, "objects": len(document["nodes"]), "bytes": len(data),
            "export_ms": figure(exports), "import_ms": figure(imports)}


def _animate(bench: Bench, hands: int, ticks: int,
             after: Callable[[], None] | None = None) -> list[float]:
    """Milliseconds of each of ``ticks`` steps: the hands' animation step applied, a tick
    and its frame encoded (``after`` each, untimed)."""
    times = []
    for n in range(ticks):
        started = time.perf_counter()
        bench.send(scenes.hand_step("c1", hands, n))
        encode(bench.scene.tick(PERIOD)[-1])
        times.append((time.perf_counter() - started) * 1000)
        if after is not None:
            after()
    return times


def max_hands(counts: list[int], ticks: int) -> dict[str, Any]:
    """For each count of animated hands, applying a step and ticking; the largest count
    whose median fits in one 60 Hz period (16.7 ms)."""
    rows, fits = [], 0
    for count in counts:
        bench = Bench(scenes.hands("c1", count))
        step = figure(_animate(bench, count, ticks))
        bench.close()
        rows.append({"hands": count, "step_ms": step})
        if step.median > PERIOD * 1000:
            break
        fits = count
    return {"rows": rows, "max_hands": fits}


def as_json(value: Any) -> Any:
    """Figures as plain dictionaries, for results.json."""
    if isinstance(value, Figure):
        return value.as_dict()
    if isinstance(value, dict):
        return {k: as_json(v) for k, v in value.items()}
    if isinstance(value, list):
        return [as_json(v) for v in value]
    return value


def dynamic(hands: int, objects: int, falling: int, ticks: int) -> dict[str, Any]:
    """A dynamic scene (default physics: 5 substeps a tick) of animated hands and objects
    dropped among them: the tick (applying a step included) over the ``falling`` ticks
    after the drop, then over ``ticks`` more once they lie on the ground, and Bullet's own
    steps (``stepSimulation``) within each of those ticks, their floor at these physics
    settings; whether the second median fits in a 60 Hz period."""
    bench = Bench(scenes.dynamic("c1", hands, objects))
    world = bench.scene.bodies.physics.dynamics  # type: ignore[union-attr]
    world.clock = time.perf_counter  # its steps timed on the tick's own clock
    drop = figure(_animate(bench, hands, falling))
    stepping: list[float] = []
    tick = figure(_animate(bench, hands, ticks, lambda: stepping.append(world.stepping * 1000)))
    steps = world.steps
    bench.close()
    return {"hands": hands, "objects": objects, "falling_ms": drop, "tick_ms": tick,
            "stepping_ms": figure(stepping), "physics_steps": steps,
            "holds_60hz": tick.median <= PERIOD * 1000}
