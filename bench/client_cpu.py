"""What a user's script costs the server: hands-10 (bench/scenes.py: the same layout and
angles as the raw driver's) animated at 60 Hz through the Python client's own loop
(``vp.set_animation`` and ``vp.run``) and through the JS client's ``setAnimation`` in
Node, each step flexing and spreading every hand's fingers.

The server's whole CPU (its web process and the scene's process) is read from /proc over
a window of the run, not the driver's: ``client_cpu_hands10_pct`` is that as a share of
one core. The drivers are the clients as shipped; only their loop's rate is set.

``python -m bench.client_cpu python|js URL SCENE SECONDS HANDS`` runs one driver.
"""

from __future__ import annotations

import math
import subprocess
import sys
import time
from typing import Any

from .live import NICE, ROOT, RunningServer, cpu_seconds
from .scenes import GRID, hand_angles

JS_DRIVER = """
import * as vp from "./clients/js/virtual-prosthetics.js";
const [url, scene, seconds, count, grid] = process.argv.slice(1);  // (node -e: no script)
await vp.connect({ url, scene });
const columns = Math.max(1, Math.ceil(Math.sqrt(count)));
const hands = [];
for (let i = 0; i < Number(count); i++) {
  const hand = new vp.EdgedHand(i % 2 === 0);
  hand.setPosition((i % columns) * grid, 0, Math.floor(i / columns) * grid);
  hands.push(hand);
}
vp.setAnimation((t) => {
  const step = Math.round(60 * t);
  for (const [i, hand] of hands.entries()) {
    hand.flexFingers(0.8 * (0.5 + 0.5 * Math.sin(step / 20 + i)));
    hand.spreadFingers(0.3 * Math.sin(step / 15 + i));
  }
}, 60);
setTimeout(() => { vp.close(); process.exit(0); }, 1000 * Number(seconds));
"""


def python_driver(url: str, scene: str, seconds: float, count: int) -> None:
    """hands-``count`` through the Python client's own animation loop."""
    import virtual_prosthetics as vp
    vp.connect(url, scene=scene)
    columns = max(1, math.ceil(math.sqrt(count)))
    hands = [vp.EdgedHand(i % 2 == 0) for i in range(count)]
    for i, hand in enumerate(hands):
        hand.set_position((i % columns) * GRID, 0, (i // columns) * GRID)

    def step(t: float) -> None:
        for hand, (flex, spread) in zip(hands, hand_angles(count, round(60 * t))):
            hand.flex_fingers(flex)
            hand.spread_fingers(spread)
    vp.set_animation(step, fps=60)
    vp.run(seconds)


def measure(running: RunningServer, client: str, count: int, seconds: float) -> dict[str, Any]:
    """The server's cores while ``client`` (python or js) animates ``count`` hands."""
    scene = f"client-{client}"
    command = ([*NICE, "node", "--input-type=module", "-e", JS_DRIVER, "--"] if client == "js"
               else [*NICE, sys.executable, "-m", "bench.client_cpu", "python"])
    driver = subprocess.Popen([*command, running.ws, scene, str(seconds + 5), str(count),
                               str(GRID)], cwd=ROOT)
    try:
        _wait_for_steps(running, scene, driver)
        pids = [running.process.pid, running.figures(scene)["pid"]]
        before, start = cpu_seconds(pids), time.monotonic()
        time.sleep(seconds * 0.8)
        cores = (cpu_seconds(pids) - before) / (time.monotonic() - start)
        figures = running.figures(scene)
    finally:
        driver.terminate()  # (measured: what is left of its run is not)
        driver.wait(60)
    return {"client": client, "hands": count, "server_cores": cores,
            "ticks_per_second": figures["ticksPerSecond"], "tick_ms_p50": figures["tickMsP50"],
            "requests_per_second": figures["requestsPerSecond"]}


def _wait_for_steps(running: RunningServer, scene: str, driver: subprocess.Popen[bytes]) -> None:
    """Until the driver's hands are made and its loop sends steps (a second of them)."""
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and driver.poll() is None:
        if running.figures(scene)["requestsPerSecond"] > 0:
            time.sleep(1.0)
            return
        time.sleep(0.1)
    raise RuntimeError(f"the {scene} driver sent no step within a minute")


if __name__ == "__main__":
    if sys.argv[1] != "python":
        raise SystemExit("the JS driver runs in Node (measure() starts it)")
    url, scene, seconds, count = sys.argv[2:6]  # (the grid is scenes.GRID here)
    python_driver(url, scene, float(seconds), int(count))
