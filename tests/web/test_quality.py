"""The viewer's drawing levels (web/src/viewer/quality.js) adapt to how long wanted
pictures wait: driven here with made-up waits, in the browser that serves the module."""

from __future__ import annotations

import pytest

from .conftest import open_viewer


# A Quality fed `waits` (ms, one list per group of pictures judged together), starting at
# level `start`: the level names it went through and where it ended.
RUN = """async ([start, groups, gap]) => {
    const { Quality, LEVELS } = await import('/web/viewer/quality.js');
    const names = [];
    const quality = new Quality(false, (level) => names.push(level.name));
    quality.index = start;
    let now = 100000;
    for (const waits of groups) {
        for (const wait of waits) { now += gap; quality.drawn(now - wait, now); }
    }
    return { names, level: quality.level.name, count: LEVELS.length };
}"""


@pytest.fixture(scope="module")
def page(browser, server):
    page = browser.new_context().new_page()
    page.goto(f"{server.http}/")
    yield page
    page.context.close()


def run(page, start: int, groups: list[list[float]], gap: float = 50) -> dict:
    return page.evaluate(RUN, [start, groups, gap])


def nine(wait: float) -> list[float]:
    return [wait] * 9


def test_slow_pictures_step_down_while_each_step_helps(page):
    result = run(page, 0, [nine(200), nine(150), nine(100), nine(60)])
    assert result["names"] == ["high", "medium", "low", "lower"]


def test_a_step_that_does_not_help_is_taken_back_and_not_retried_at_once(page):
    result = run(page, 2, [nine(200), nine(200), nine(200), nine(200)])
    # low came no sooner than medium: back to medium, which stays while the floor holds
    assert result["names"] == ["low", "medium"]
    assert result["level"] == "medium"


def test_after_a_while_the_step_is_tried_again(page):
    # the same, but the groups come 11 s apart: other pages sharing the GPU may be gone
    result = run(page, 2, [nine(200), nine(200), nine(200), nine(150), nine(100)], gap=1250)
    assert result["names"] == ["low", "medium", "low", "lower", "lowest"]


def test_quick_pictures_for_five_seconds_step_back_up(page):
    result = run(page, 4, [nine(10)] * 14, gap=50)   # 6.3 s of 10 ms waits
    assert result["names"] == ["low"]
    assert run(page, 4, [nine(10)] * 9, gap=50)["names"] == []   # 4 s: not yet


def test_the_coarsest_level_is_the_last(page):
    result = run(page, 5, [nine(200), nine(150), nine(100)])
    assert result["names"] == ["rough"] and result["level"] == "rough"


def test_a_held_level_stays_whatever_pictures_cost(page):
    held = page.evaluate("""async () => {
        const { Quality } = await import('/web/viewer/quality.js');
        const names = [];
        const quality = new Quality(true, (level) => names.push(level.name), 'lower');
        let now = 100000;
        for (let k = 0; k < 90; k++) { now += 50; quality.drawn(now - (k < 45 ? 300 : 1), now); }
        return { names, level: quality.level.name };
    }""")
    assert held == {"names": [], "level": "lower"}


def test_an_unknown_level_is_told_and_the_viewer_adapts_from_its_usual_start(page):
    messages = []
    page.on("console", lambda message: messages.append(message.text))
    level = page.evaluate("""async () => {
        const { Quality } = await import('/web/viewer/quality.js');
        const quality = new Quality(true, () => {}, 'sharpest');
        let now = 100000;
        for (let k = 0; k < 9; k++) { now += 50; quality.drawn(now - 300, now); }
        return quality.level.name;
    }""")
    assert level == "low"  # software starts at medium; slow pictures stepped it down
    assert any("quality=sharpest: no such level" in m and "rough" in m for m in messages)


def test_a_viewer_asked_for_a_level_draws_at_it(browser, pages, server, scene_name):
    viewer = open_viewer(browser, pages, server, f"scene={scene_name}&quality=rough")
    drawn = viewer.evaluate("""() => ({ level: VP.quality.level.name,
        ratio: VP.renderer.getPixelRatio(), shadows: VP.renderer.shadowMap.enabled })""")
    assert drawn == {"level": "rough", "ratio": 0.3, "shadows": False}
