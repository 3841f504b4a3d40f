"""What the Gymnasium environments give (``virtual_prosthetics.gym``; Grasp-v0, the edged
hand, the light ball): steps a second of one environment (``gym_steps_per_s``), of
Gymnasium's vector environment over two scenes against the same over one
(``gym_vector2_speedup``; each environment in a process of its own, stepping its scene's
process; ``vector2_over_one_env``: against one environment without the vector's
processes), a reset's wall time
(``gym_reset_ms``: the scene restored in its process and the first observation read), and
a step's wall time through the server over the wall time of the same tick of the same
scene in-process (``gym_step_overhead``: the scene's document run by the core itself, the
same motor targets set before each tick; the median of three rounds)."""

from __future__ import annotations

import json
import statistics
import time
import urllib.request
from typing import Any

import gymnasium
import numpy as np

import virtual_prosthetics.gym  # noqa: F401 (registers the environments)
from server.core.kit.ids import owner_of
from server.core.protocol.operations import Operations
from server.core.protocol.scene_document import import_scene
from server.core.scene.scene import Scene
from tests.conftest import start_server, stop_server

ENV = "VirtualProsthetics/Grasp-v0"
EPISODE_STEPS = 180  # of random actions: before the hold, where an open hand's drop ends one


def measure(steps: int, resets: int) -> dict[str, Any]:
    """``steps`` steps of one environment and of two side by side; ``resets`` resets."""
    running = start_server("--no-demo")
    try:
        env = gymnasium.make(ENV, url=running.ws)
        try:
            one = _steps_per_s(env, steps)
            reset_ms = [_reset_ms(env, seed) for seed in range(resets)]
            overhead = _overhead(env, running.http, steps)
        finally:
            env.close()
        vector1, vector2 = (_vector_steps_per_s(running.ws, width, steps) for width in (1, 2))
    finally:
        stop_server(running)
    return {"steps_per_s": one, "vector1_steps_per_s": vector1, "vector2_steps_per_s": vector2,
            "vector2_speedup": vector2 / vector1, "vector2_over_one_env": vector2 / one,
            "reset_ms": statistics.median(reset_ms), "reset_ms_max": max(reset_ms), **overhead}


def _vector_steps_per_s(url: str, width: int, steps: int) -> float:
    """Steps a second of Gymnasium's vector environment over ``width`` scenes (each
    environment in a process of its own, as ``async`` makes them)."""
    vector = gymnasium.make_vec(ENV, num_envs=width, vectorization_mode="async", url=url)
    try:
        return _steps_per_s(vector, steps, width)
    finally:
        vector.close()


def _actions(space: Any, count: int) -> np.ndarray:
    return np.random.default_rng(1).uniform(-1, 1, (count, *space.shape)).astype(np.float32)


def _steps_per_s(env: Any, steps: int, width: int = 1) -> float:
    """Steps (of every environment of a vector) a second, resets left out of the time."""
    actions, spent, done = _actions(env.action_space, steps), 0.0, 0
    while done < steps:
        env.reset(seed=done)
        chunk = actions[done:done + min(EPISODE_STEPS, steps - done)]
        started = time.perf_counter()
        for action in chunk:
            env.step(action)
        spent += time.perf_counter() - started
        done += len(chunk)
    return width * steps / spent


def _reset_ms(env: Any, seed: int) -> float:
    started = time.perf_counter()
    env.reset(seed=seed)
    return 1000 * (time.perf_counter() - started)


OVERHEAD_ROUNDS = 3  # of the server's episode and the same in-process, one after the other


def _overhead(env: Any, http: str, steps: int) -> dict[str, float]:
    """A step's wall time through the server and the same scene's tick in-process with the
    same motor targets and wrist positions, in rounds one after the other (so that both
    see the machine as it is then); the median round's."""
    rounds = [_overhead_round(env, http, min(steps, EPISODE_STEPS))
              for _ in range(OVERHEAD_ROUNDS)]
    through, in_process = (statistics.median(r[k] for r in rounds) for k in (0, 1))
    return {"step_ms": 1000 * through, "in_process_tick_ms": 1000 * in_process,
            "step_overhead": statistics.median(r[0] / r[1] for r in rounds)}


def _overhead_round(env: Any, http: str, steps: int) -> tuple[float, float]:
    """Seconds a step takes through the server, and the same tick in-process. Both are wall
    times: CPU time in-process leaves out what the machine took for other things, and the
    ratio then measured the machine's load (1.66 in a full bench, 1.39 alone) as well."""
    inner = env.unwrapped
    env.reset(seed=0)
    document = _document(http, inner.session.name)
    actions = _actions(env.action_space, steps)
    wrist = []
    started = time.perf_counter()
    for action in actions:
        env.step(action)
        wrist.append(inner.trial.hand_position())  # (from the mirror: no message)
    through = (time.perf_counter() - started) / len(actions)
    scene = Scene("bench-in-process")
    import_scene(scene, document)
    hand = inner.first.hand.id
    ops = Operations(scene, owner_of(hand))
    scene.clock.pause(owner_of(hand))  # its ticks exact, as a stepped scene's (no CPU budget)
    scene.watches.add(inner.first.sensor.id, owner_of(hand))  # frames tell its contacts, as there
    angles = [list(inner.actions.targets(action).values) for action in actions]
    started = time.perf_counter()
    for values, position in zip(angles, wrist):
        ops.call(hand, "setPosition", list(position))
        ops.call(hand, "setAngles", values)
        scene.tick(1 / 60)
    in_process = (time.perf_counter() - started) / len(actions)
    scene.close()
    return through, in_process


def _document(http: str, scene: str) -> dict[str, Any]:
    """The scene's document, as REST exports it."""
    with urllib.request.urlopen(f"{http}/api/scenes/{scene}/export", timeout=60) as answer:
        return json.loads(answer.read())  # type: ignore[no-any-return]
