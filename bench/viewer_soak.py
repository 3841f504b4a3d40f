"""A viewer left open while a script keeps building, moving and deleting robots.

    .venv/bin/python bench/viewer_soak.py [minutes]      (default 3)

Every few seconds the script replaces an edged hand (so objects come and go) and flexes
the fingers at 30 Hz; once a minute the page's JS heap, its GPU geometries and textures,
its object count and how many frames it has handled and pictures drawn are sampled. A
leak shows as a growing heap or geometry count; a slowdown as fewer frames handled (or
pictures drawn) per minute.
"""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

from playwright.sync_api import sync_playwright

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import virtual_prosthetics as vp  # noqa: E402
from tests.conftest import start_server, stop_server  # noqa: E402
from tests.web.conftest import CHROMIUM, FLAGS  # noqa: E402

SAMPLE = """() => ({heapMB: performance.memory.usedJSHeapSize / 1e6,
  geometries: VP.renderer.info.memory.geometries, textures: VP.renderer.info.memory.textures,
  objects: VP.objects.size, frames: VP.frames, rendered: VP.rendered})"""


def main(minutes: float) -> list[dict[str, float]]:
    server = start_server("--no-demo")
    samples = []
    try:
        scene = vp.connect(server.ws, scene="soak")
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM,
                                                 args=[*FLAGS, "--enable-precise-memory-info",
                                                       "--js-flags=--expose-gc"])
            page = browser.new_context(viewport={"width": 480, "height": 320}).new_page()
            page.goto(f"{server.http}/view?scene=soak&touch-color=red")
            page.wait_for_function("() => window.VP && VP.snapshots > 0")
            started = last_sample = time.monotonic()
            hand, built = None, 0.0
            while time.monotonic() - started < minutes * 60:
                now = time.monotonic()
                if hand is None or now - built > 5:
                    if hand is not None:
                        hand.delete()
                    hand, built = vp.EdgedHand(), now
                    hand.set_position(0, 0.2, 0)
                    hand.add_gui("Soak")
                hand.flex_fingers(0.8 * (0.5 + 0.5 * math.sin(now * 2)))
                if now - last_sample >= 60 or not samples:
                    page.evaluate("() => window.gc && window.gc()")
                    samples.append({"minute": round((now - started) / 60, 1),
                                    **page.evaluate(SAMPLE)})
                    print(json.dumps(samples[-1]), flush=True)
                    last_sample = now
                time.sleep(1 / 30)
            browser.close()
        scene.close()
    finally:
        stop_server(server)
    return samples


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 3)
