"""The viewer's stage (web/src/viewer/stage.js): where WebGL draws in software (as here),
pictures come at most SOFTWARE_FPS a second, or as many as the page's ?fps= says; an
empty scene's logo turns at most SOFTWARE_TURNS times a second there (logo.js)."""

from __future__ import annotations

import math
import re
import threading
import time

import pytest

from tests.conftest import ROOT
from tests.web.conftest import open_viewer, red_box_on_a_motor, wait_until

PICTURES = 10
# how long (the page's own clock, ms) the next `count` pictures took: a slow or loaded
# machine takes longer, which the cap allows; a page drawing past its cap takes less
TIME = """async (count) => {
    const first = VP.rendered, started = performance.now();
    while (VP.rendered < first + count) await new Promise((resolve) => setTimeout(resolve, 10));
    return performance.now() - started;
}"""


def _constant(path: str, name: str) -> int:
    source = (ROOT / "web" / "src" / "viewer" / path).read_text()
    return int(re.search(rf"export const {name} = (\d+);", source).group(1))


@pytest.mark.parametrize("query, most", [("", _constant("stage.js", "SOFTWARE_FPS")), ("&fps=4", 4)])
def test_a_moving_robot_is_drawn_no_faster_than_the_cap(browser, pages, server, scene, scene_name,
                                                        query, most):
    _, motor, _ = red_box_on_a_motor()
    scene.sync()
    page = open_viewer(browser, pages, server, f"scene={scene_name}{query}")
    wait_until(page, "(id) => VP.objects.has(id)", motor.id)
    swinging = threading.Event()

    def swing() -> None:  # a new angle every 1/30 s: pictures are wanted all the time
        k = 0
        while not swinging.is_set():
            motor.set_angle(math.sin(k / 5))
            k += 1
            time.sleep(1 / 30)
    swinger = threading.Thread(target=swing)
    swinger.start()
    try:
        ms = page.evaluate(TIME, PICTURES)
    finally:
        swinging.set()
        swinger.join()
    assert PICTURES <= most * ms / 1000 + 1, f"{PICTURES} pictures in {ms:.0f} ms"


def test_an_empty_scenes_logo_turns_no_more_than_its_software_rate(browser, pages, server, scene_name):
    # the findings: a viewer of an empty scene took 1.7 cores of SwiftShader at 29 pictures a
    # second, then 1.25 cores at the 15 of the cap, for a decoration
    turns = _constant("logo.js", "SOFTWARE_TURNS")
    page = open_viewer(browser, pages, server, f"scene={scene_name}")
    page.evaluate(TIME, 2)  # (the first pictures: the snapshot's)
    before = page.evaluate("() => VP.scene.getObjectByName('logo').rotation.y")
    ms = page.evaluate(TIME, 4)  # the logo keeps turning: pictures keep coming
    assert 4 <= turns * ms / 1000 + 1, f"4 pictures in {ms:.0f} ms"
    assert page.evaluate("() => VP.scene.getObjectByName('logo').rotation.y") != before
