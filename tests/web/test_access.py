"""Pages on a server with tokens: a page takes its token from its URL; without the right
one the viewer says why it was refused, and a 1.0 page cannot build."""

import time

import pytest

from ..conftest import WAIT_SECONDS, start_server, stop_server
from .conftest import CALM, open_page, open_viewer, wait_until

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first

CONTROL, VIEW = "page-control-token", "page-view-token"


@pytest.fixture(scope="module")
def locked():
    running = start_server("--no-demo", "--token", CONTROL, "--view-token", VIEW)
    running.token = VIEW  # the test's own REST reads
    yield running
    stop_server(running)


def test_pages_with_the_token_build_and_watch(browser, pages, locked):
    open_page(browser, pages, f"{locked.http}/examples/two-hands.html?scene=locked&token={CONTROL}&{CALM}")
    deadline = time.monotonic() + WAIT_SECONDS
    while len(locked.robots("locked")) < 2:
        assert time.monotonic() < deadline, "the page's hands never reached the server"
        time.sleep(0.2)
    ids = [n["id"] for n in locked.nodes("locked")]
    viewer = open_viewer(browser, pages, locked, f"scene=locked&token={VIEW}&{CALM}")
    wait_until(viewer, "(ids) => ids.every((id) => VP.objects.has(id))", ids)


def test_a_viewer_without_the_view_token_says_why(browser, pages, locked):
    page = open_page(browser, pages, f"{locked.http}/view?scene=locked")
    wait_until(page, "() => document.getElementById('status').textContent.includes('refused')")
    assert "view token" in page.inner_text("#status")
    controller = open_page(browser, pages, f"{locked.http}/view?scene=locked&role=controller"
                                           f"&token={VIEW}")
    wait_until(controller, "() => document.getElementById('status').textContent.includes('refused')")
    assert "needs its token" in controller.inner_text("#status")


def test_the_index_passes_its_token_on_to_the_pages_it_links(browser, pages, locked):
    page = open_page(browser, pages, f"{locked.http}/?token={CONTROL}")
    wait_until(page, "() => document.querySelector('#scenes tbody a')")
    hrefs = page.evaluate("() => [...document.querySelectorAll('a[href^=\"/view\"], "
                          "a[href^=\"/examples/\"]')].map((a) => a.getAttribute('href'))")
    assert hrefs and all(f"token={CONTROL}" in href for href in hrefs)
