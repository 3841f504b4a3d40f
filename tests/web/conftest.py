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
# A query that has pages and viewers draw two pictures a second (the viewer's ?fps=), for
# tests that check what pages make and move rather than their pictures (test_stage.py has
# the cap): an animated 1.0 page drawn at the software cap took 1.5 cores against 0.8
CALM = "fps=2"


@pytest.fixture(scope="module")
def browser() -> Iterator[Browser]:
    """Chromium for one test file: playwright's sync API keeps an event loop running in
    this thread while it is open, which tests of other files run by the same worker
    (asyncio.run) must not find."""
    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield chromium
        chromium.close()


@pytest.fixture
def pages(browser: Browser) -> Iterator[list[Page]]:
    """A list to open pages into; each is closed after the test, with its errors checked."""
    opened: list[Page] = []
    yield opened
    for page in opened:
        close_page(page)


def close_page(page: Page) -> None:
    """Close a page (software WebGL is slow: fewer open pages, faster tests); it must have
    had no uncaught error."""
    if page.is_closed():
        return
    errors = page.evaluate("() => window.__errors || []")
    page.context.close()
    assert errors == [], errors


def open_page(browser: Browser, pages: list[Page], url: str) -> Page:
    """A new page at ``url`` that records uncaught errors in ``window.__errors``."""
    page = browser.new_context(viewport=VIEWPORT).new_page()
    page.set_default_timeout(WAIT_SECONDS * 1000)  # a guard: software WebGL on a loaded core
    page.add_init_script("window.__errors = []; window.addEventListener('error', "
                         "(e) => window.__errors.push(String(e.message)));")
    pages.append(page)
    page.goto(url)
    return page


def open_viewer(browser: Browser, pages: list[Page], server, query: str) -> Page:
    """A viewer page that has its first snapshot."""
    page = open_page(browser, pages, f"{server.http}/view?{query}")
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
