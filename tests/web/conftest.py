"""Real headless Chromium (Debian's package, software WebGL) driven by Playwright."""

from __future__ import annotations

from typing import Iterator

import pytest
from playwright.sync_api import Browser, Page, sync_playwright

import virtual_prosthetics as vp
from tests.conftest import WAIT_SECONDS
from tests.clients.python.conftest import scene  # noqa: F401  (a fixture, shared)

CHROMIUM = "/usr/bin/chromium"
FLAGS = ["--no-sandbox", "--use-angle=swiftshader",
         "--enable-unsafe-swiftshader", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run"]
VIEWPORT = {"width": 800, "height": 500}
# The drawing level test viewers hold (the viewer's ?quality=, unless a test's query names
# one): no shadows, 0.6 of the pixels. An open viewer's pictures (two a second) cost the
# GPU process 0.10 of a core at this level against 0.25 at the level software WebGL starts
# at; the tests' screenshots find their colours in the same places at either level
# (test_quality.py has the levels)
LEVEL = "quality=lower"
# A query that has pages and viewers draw two pictures a second (the viewer's ?fps=), for
# tests that check what pages make and move rather than their pictures (test_stage.py has
# the cap): an animated 1.0 page drawn at the software cap took 1.5 cores against 0.8
CALM = f"fps=2&{LEVEL}"


@pytest.fixture(scope="module")
def browser() -> Iterator[Browser]:
    """Chromium for one test file: playwright's sync API keeps an event loop running in
    this thread while it is open, which tests of other files run by the same worker
    (asyncio.run) must not find."""
    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield chromium
        chromium.close()


class Tabs(list):
    """The pages one test opened, taken from its file's idle tabs: a page navigated from
    one test's address to the next costs the browser about 1.1 CPU-s to a viewer's first
    snapshot, against 2.6 for a new page in a new context (its renderer process, code
    cache and WebGL start again), and the suite opens about 150."""

    def __init__(self, idle: list[Page]) -> None:
        super().__init__()
        self.idle = idle

    def take(self, browser: Browser) -> Page:
        """An idle tab of this file, else a new one that records uncaught errors in
        ``window.__errors`` (at every navigation)."""
        if self.idle:
            page = self.idle.pop()
        else:
            page = browser.new_context(viewport=VIEWPORT).new_page()
            page.set_default_timeout(WAIT_SECONDS * 1000)  # a guard: software WebGL, loaded core
            page.add_init_script("window.__errors = []; window.addEventListener('error', "
                                 "(e) => window.__errors.push(String(e.message)));")
        self.append(page)
        return page

    def release(self, page: Page) -> None:
        """Done with ``page``: it must have had no uncaught error."""
        errors = self.leave(page)
        assert errors == [], errors

    def leave(self, page: Page) -> list[str]:
        """The uncaught errors of ``page``, which leaves its address (its sockets close as
        a closed page's do) and waits idle for the next test."""
        self.remove(page)
        if page.is_closed():
            return []
        errors = page.evaluate("() => window.__errors || []")
        page.goto("about:blank")
        self.idle.append(page)
        return errors


@pytest.fixture(scope="module")
def idle_tabs(browser: Browser) -> list[Page]:
    """Pages of this file's browser that no test is using (closed with it)."""
    return []


@pytest.fixture
def pages(idle_tabs: list[Page]) -> Iterator[Tabs]:
    """A list to open pages into; each is released after the test, its errors checked."""
    opened = Tabs(idle_tabs)
    yield opened
    errors = [error for page in list(opened) for error in opened.leave(page)]
    assert errors == [], errors


def open_page(browser: Browser, pages: Tabs, url: str) -> Page:
    """A page at ``url``, one of ``pages``, that records uncaught errors in ``window.__errors``."""
    page = pages.take(browser)
    page.goto(url)
    return page


def open_viewer(browser: Browser, pages: Tabs, server, query: str) -> Page:
    """A viewer page that has its first snapshot (at :data:`LEVEL` unless ``query`` names
    a level)."""
    level = "" if "quality=" in query else f"&{LEVEL}"
    page = open_page(browser, pages, f"{server.http}/view?{query}{level}")
    wait_until(page, "() => window.VP && window.VP.snapshots > 0")
    return page


def wait_until(page: Page, script: str, arg=None, timeout: float = WAIT_SECONDS * 1000) -> None:
    """Wait until a JavaScript predicate holds in the page."""
    page.wait_for_function(script, arg=arg, timeout=timeout)


def red_box_on_a_motor() -> tuple[vp.Robot, vp.MotorZ, vp.Box]:
    """A robot whose MotorZ (at the origin) carries a red box 1 high, standing up at angle 0."""
    robot = vp.Robot()
    motor = vp.MotorZ(-2, 2)
    box = vp.Box(0.3, 1, 0.3, "red")
    robot.attach_chain(motor)
    box.attach_to_slot(motor)
    box.set_position(0, 0.5, 0)
    return robot, motor, box
