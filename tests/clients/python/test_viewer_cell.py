"""``session.show()``: the scene's live viewer in a notebook cell (an IFrame of ``/view``),
drawn by Chromium as Jupyter would insert it."""

from __future__ import annotations

import virtual_prosthetics as vp
from tests.web.conftest import browser  # noqa: F401  (a fixture, shared)
from tests.web.conftest import wait_until


def test_a_cell_shows_the_scenes_live_viewer(scene, server, browser):  # noqa: F811
    robot = vp.Robot()
    robot.attach_chain(vp.MotorZ(), vp.EdgedFinger())
    robot.add_gui("Arm")
    scene.sync()
    cell = vp.show(width=640, height=400, role="controller")
    assert repr(cell) == f"watch at {server.http}/view?scene={scene.name}&role=controller"
    page = browser.new_page()
    try:
        page.set_content(cell._repr_html_())  # what a notebook puts in the cell's output
        frame = page.frame_locator("iframe")
        assert page.locator("iframe").bounding_box()["width"] == 640
        viewer = next(f for f in page.frames if "/view?" in f.url)
        wait_until(viewer, "(id) => window.VP && VP.objects.has(id) && VP.drawn()", robot.id)
        assert frame.locator(".lil-gui .lil-title").first.inner_text() == "Arm"
    finally:
        page.close()


def test_the_viewer_address_carries_the_token_when_the_session_has_one():
    from virtual_prosthetics.viewer_cell import viewer_url
    assert viewer_url("wss://lab.example:8443", "a b", token="t1") == \
        "https://lab.example:8443/view?scene=a+b&token=t1"
