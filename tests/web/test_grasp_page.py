"""The grasp example (web/examples/grasp.html) in headless Chromium: a dynamic scene where
an EdgedHand comes down over a ball on a table and closes on it, and a viewer shows it."""

from __future__ import annotations

import time

from .conftest import open_page, open_viewer, wait_until
from .picture import Picture, project

TABLE_TOP = 1.4


def _node(server, scene: str, kind: str) -> dict | None:
    return next((n for n in server.nodes(scene) if n["type"] == kind), None)


def test_the_grasp_page_closes_the_hand_on_the_ball_and_a_viewer_shows_it(
        browser, pages, server, scene_name):
    open_page(browser, pages, f"{server.http}/examples/grasp.html?scene={scene_name}")
    deadline = time.monotonic() + 60
    pressed = 0.0
    while time.monotonic() < deadline and pressed == 0.0:
        metrics = server.get("/api/metrics")["scenes"].get(scene_name, {})
        ball = _node(server, scene_name, "Ball")
        if ball and ball["position"][1] > TABLE_TOP:  # resting on the table, not fallen through
            weight = ball["mass"] * server.get(f"/api/scenes/{scene_name}")["physics"]["gravity"]
            if metrics.get("peakForceN", 0) > 1.5 * weight:  # squeezed: more than its weight
                pressed = metrics["peakForceN"]
        time.sleep(0.2)
    assert pressed, "the hand never pressed on the ball"
    hand = _node(server, scene_name, "EdgedHand")
    angles = [n["angle"] for n in server.nodes(scene_name) if n["type"].startswith("Motor")]
    assert hand is not None and min(angles) < -0.5  # its fingers closed
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}")
    wait_until(viewer, "() => VP.objects.size > 10")
    ball = _node(server, scene_name, "Ball")
    picture = Picture(viewer.screenshot())
    camera = server.get(f"/api/scenes/{scene_name}")["camera"]
    red, green, blue = picture.at(project(ball["position"], camera["position"], camera["target"],
                                          picture.size), radius=1)
    assert red > 150 and blue < 100, (red, green, blue)  # orange: the ball, where the server has it
