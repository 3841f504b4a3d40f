"""``/docs`` and ``/redoc`` in Chromium with every address but the server's refused, as on a
machine without the internet: the API's operations are listed on both."""

from __future__ import annotations

from tests.web.conftest import browser  # noqa: F401  (a fixture, shared)
from tests.web.conftest import VIEWPORT, wait_until


def _offline_page(browser, server, path: str):  # noqa: F811
    context = browser.new_context(viewport=VIEWPORT)
    refused: list[str] = []

    def only_the_server(route) -> None:
        if route.request.url.startswith(server.http):
            route.continue_()
        else:
            refused.append(route.request.url)
            route.abort("internetdisconnected")
    context.route("**/*", only_the_server)
    page = context.new_page()
    page.goto(f"{server.http}{path}")
    return page, refused


def test_the_swagger_page_lists_the_api_offline(browser, server):  # noqa: F811
    """Found: a blank /docs (Swagger UI from a CDN: SwaggerUIBundle is not defined)."""
    page, refused = _offline_page(browser, server, "/docs")
    try:
        wait_until(page, "() => document.querySelectorAll('.opblock').length > 20")
        paths = page.locator(".opblock-summary-path").all_inner_texts()
        assert "/api/scenes" in paths and "/api/scenes/{scene}/picture" in paths
        assert refused == []
    finally:
        page.context.close()


def test_the_redoc_page_lists_the_api_offline(browser, server):  # noqa: F811
    page, refused = _offline_page(browser, server, "/redoc")
    try:
        wait_until(page, "() => document.body.innerText.includes('/api/scenes/{scene}/picture')")
        # all but ReDoc's own footer logo, which its bundle always asks of its CDN (offline:
        # a missing picture in the sidebar's corner, nothing else)
        assert "Virtual Prosthetics" in page.title()
        assert [url for url in refused if not url.endswith("/redoc/logo-mini.svg")] == []
    finally:
        page.context.close()
