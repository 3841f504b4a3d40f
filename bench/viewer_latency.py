"""How soon three viewers in headless Chromium show a motor angle a Python script set.

Starts its own server; needs Debian's chromium (`make test` installs it). The time runs
from the script's set_angle call (wall clock) until the last of the three pages handled
the frame with the new angle (the page notes the wall-clock time in
``VP.angleTimes``), so it includes the client, the server's tick, the WebSocket and the
page's message handling, and any picture the page was busy drawing (software WebGL here).
"""

from __future__ import annotations

import json
import statistics
import sys
import time
from pathlib import Path

from playwright.sync_api import sync_playwright

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import virtual_prosthetics as vp  # noqa: E402
from tests.conftest import start_server, stop_server  # noqa: E402
from tests.web.conftest import CHROMIUM, FLAGS, VIEWPORT  # noqa: E402

ROUNDS = 30


def main() -> dict[str, float]:
    server = start_server("--no-demo")
    try:
        scene = vp.connect(server.ws, scene="latency")
        robot = vp.Robot()
        motor = vp.MotorZ(-2, 2)
        robot.attach_chain(motor, vp.EdgedFinger())
        scene.sync()
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
            pages = [browser.new_context(viewport=VIEWPORT).new_page() for _ in range(3)]
            for page in pages:
                page.goto(f"{server.http}/view?scene=latency")
                page.wait_for_function("(id) => window.VP && VP.objects.has(id)", arg=motor.id)
            delays = []
            for k in range(ROUNDS):
                angle = round(-1 + 2 * k / ROUNDS, 3)
                started = time.time() * 1000
                motor.set_angle(angle)
                arrived = []
                for page in pages:
                    page.wait_for_function("([id, a]) => VP.angle(id) === a", arg=[motor.id, angle],
                                           polling=20)
                    arrived.append(page.evaluate("(id) => VP.angleTimes.get(id)", motor.id))
                delays.append(max(arrived) - started)
                time.sleep(0.2)
            render_ms = [page.evaluate("() => VP.renderMs") for page in pages]
            browser.close()
        scene.close()
    finally:
        stop_server(server)
    delays.sort()
    return {"rounds": ROUNDS, "median_ms": statistics.median(delays),
            "p95_ms": delays[int(0.95 * ROUNDS) - 1], "max_ms": delays[-1],
            "last_render_ms": render_ms}


if __name__ == "__main__":
    print(json.dumps(main(), indent=1))
