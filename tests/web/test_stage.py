"""The viewer's stage (web/src/viewer/stage.js): where WebGL draws in software (as here),
pictures come at most SOFTWARE_FPS a second, or as many as the page's ?fps= says."""

from __future__ import annotations

import re

import pytest

from tests.conftest import ROOT
from tests.web.conftest import open_viewer

PICTURES = 10
# how long (the page's own clock, ms) the next `count` pictures took: a slow or loaded
# machine takes longer, which the cap allows; a page drawing past its cap takes less
TIME = """async (count) => {
    const first = VP.rendered, started = performance.now();
    while (VP.rendered < first + count) await new Promise((resolve) => setTimeout(resolve, 10));
    return performance.now() - started;
}"""


def _software_fps() -> int:
    source = (ROOT / "web" / "src" / "viewer" / "stage.js").read_text()
    return int(re.search(r"export const SOFTWARE_FPS = (\d+);", source).group(1))


@pytest.mark.parametrize("query, most", [("", _software_fps()), ("&fps=4", 4)])
def test_an_empty_scenes_spinning_logo_is_drawn_no_faster_than_the_cap(
        browser, pages, server, scene_name, query, most):
    # the finding: a viewer of an empty scene took 1.7 cores of SwiftShader, 29 pictures a second
    page = open_viewer(browser, pages, server, f"scene={scene_name}{query}")
    ms = page.evaluate(TIME, PICTURES)  # the logo keeps turning: pictures keep coming
    assert PICTURES <= most * ms / 1000 + 1, f"{PICTURES} pictures in {ms:.0f} ms"
