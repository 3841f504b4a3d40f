"""The index page in a real browser: the scenes the server runs, with links to watch them."""

from __future__ import annotations

import json
from pathlib import Path

from .conftest import open_page, wait_until


def test_the_index_lists_the_scenes_with_links_to_watch(browser, pages, server):
    page = open_page(browser, pages, f"{server.http}/")
    wait_until(page, "() => document.querySelectorAll('#scenes tbody tr').length > 0")
    row = page.locator("#scenes tbody tr", has_text="default").first
    assert row.locator("a", has_text="watch").get_attribute("href") == "/view?scene=default"
    assert "control" in row.inner_text()
    export = row.locator("a", has_text="export").get_attribute("href")
    assert export == "/api/scenes/default/export"
    with page.expect_download() as download:  # the scene as a document, as a file
        row.locator("a", has_text="export").click()
    saved = download.value
    assert saved.suggested_filename == "default.json"
    assert json.loads(Path(saved.path()).read_text())["format"] == "virtual-prosthetics-scene"


def test_every_example_page_is_linked_from_the_index(browser, pages, server):
    examples = sorted(f"/examples/{p.name}" for p in (Path(__file__).parents[2] / "web" / "examples").glob("*.html"))
    page = open_page(browser, pages, f"{server.http}/")
    links = page.evaluate("() => [...document.querySelectorAll('a')].map((a) => a.getAttribute('href'))")
    assert [e for e in examples if e not in {link.partition("?")[0] for link in links}] == []
    assert len(examples) >= 12


def test_the_commands_shown_name_this_servers_address(browser, pages, server):
    """Found: `/` showed `VP_URL=ws://127.0.0.1:8000 …` when the server ran on another port."""
    page = open_page(browser, pages, f"{server.http}/")
    wait_until(page, "() => document.querySelectorAll('#scenes tbody tr').length > 0")
    commands = page.locator("code").all_inner_texts()
    step5 = next(c for c in commands if "page.mjs digger" in c)
    assert step5.startswith(f"VP_URL={server.ws} ") and ":8000" not in " ".join(commands)
    assert any(c.startswith(f"{server.ws}/ws?scene=") for c in commands)
