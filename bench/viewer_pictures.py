"""How many pictures viewers draw on software WebGL, and how late they handle frames.

Starts its own server with the demo (six hands moving every tick) and opens VIEWERS
pages of it in headless Chromium (SwiftShader, as our machines have), for SECONDS.
Per page: pictures per second, draw times, and frame lateness: when the page had handled
a frame (its wall clock, VP.frameLog) less when the browser received it from the network
(Playwright's WebSocket events, same machine and clock), so a frame that waited behind a
picture counts as late by that wait; and the page's long tasks (main thread busy > 50 ms).

    .venv/bin/python bench/viewer_pictures.py [viewers=3] [seconds=20] [query]
"""

from __future__ import annotations

import json
import statistics
import sys
import time
from pathlib import Path

from playwright.sync_api import sync_playwright

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.conftest import start_server, stop_server  # noqa: E402
from tests.web.conftest import CHROMIUM, FLAGS, VIEWPORT  # noqa: E402

LATE_MS = 50


def page_figures(page, seconds: float, arrivals: dict[int, float]) -> dict[str, float]:
    before = page.evaluate("() => [VP.rendered, performance.now(), VP.longTasks.length]")
    arrivals.clear()
    page.wait_for_timeout(seconds * 1000)  # Playwright notes arrivals meanwhile
    rendered, now, tasks = page.evaluate("() => [VP.rendered, performance.now(), VP.longTasks.length]")
    handled = dict(page.evaluate("() => VP.frameLog"))
    draws = sorted(page.evaluate(f"() => VP.renderLog.slice(-{rendered - before[0]})"))
    long_tasks = page.evaluate(f"() => VP.longTasks.slice({before[2]})")
    lateness = sorted(max(0.0, handled[seq] - t) for seq, t in arrivals.items() if seq in handled)
    return {"pictures_per_s": round((rendered - before[0]) * 1000 / (now - before[1]), 1),
            "draw_ms_p50": round(statistics.median(draws), 1) if draws else None,
            "draw_ms_max": round(draws[-1], 1) if draws else None,
            "frames": len(lateness),
            "late_ms_p50": round(statistics.median(lateness), 1),
            "late_ms_p99": round(lateness[int(0.99 * len(lateness)) - 1], 1),
            "late_ms_max": round(lateness[-1], 1),
            "late_pct": round(100 * sum(x > LATE_MS for x in lateness) / len(lateness), 2),
            "long_tasks": len(long_tasks), "long_task_max_ms": round(max(long_tasks, default=0), 1),
            "level": page.evaluate("() => VP.quality.level.name"),
            "status": page.evaluate("() => document.getElementById('status').textContent")}


def follow_frames(page, arrivals: dict[int, float]) -> None:
    """Note when each frame reaches the browser (before the page's main thread sees it)."""
    def received(payload: str | bytes) -> None:
        at = time.time() * 1000
        text = payload if isinstance(payload, str) else payload.decode()
        if text.startswith('{"op":"frame"'):
            arrivals[json.loads(text)["seq"]] = at
    page.on("websocket", lambda ws: ws.on("framereceived", received))


def main(viewers: int = 3, seconds: float = 20, query: str = "") -> list[dict[str, float]]:
    server = start_server()
    try:
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
            pages = [browser.new_context(viewport=VIEWPORT).new_page() for _ in range(viewers)]
            arrivals: list[dict[int, float]] = [{} for _ in pages]
            for page, noted in zip(pages, arrivals):
                follow_frames(page, noted)
                page.goto(f"{server.http}/view?scene=default{query}")
                page.wait_for_function("() => window.VP && VP.rendered > 5", timeout=60_000)
            time.sleep(3)  # past the first pictures (shaders compiled)
            results: list[dict[str, float]] = []
            started = time.monotonic()
            for page, noted in zip(pages, arrivals):  # one after another, all drawing
                results.append(page_figures(page, seconds / viewers, noted))
            results.append({"seconds": round(time.monotonic() - started, 1)})
            browser.close()
    finally:
        stop_server(server)
    return results


if __name__ == "__main__":
    args = sys.argv[1:]
    print(json.dumps(main(int(args[0]) if args else 3, float(args[1]) if len(args) > 1 else 20,
                         args[2] if len(args) > 2 else ""), indent=1))
