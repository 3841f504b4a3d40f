"""``report`` against the real server: runs side by side, every trial in CSV and JSON, a
page of plots drawn in Chromium."""

import contextlib
import csv
import io
import json

import pytest
from PIL import Image

from tests.web.conftest import browser  # noqa: F401  (a fixture, shared)
from virtual_prosthetics.tasks.__main__ import main
from virtual_prosthetics.tasks.report import seeds

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first


@pytest.fixture(scope="module")
def made(server, tmp_path_factory):
    """A report of two hands at one seed (for the suite's time: seeds multiply runs as hands
    do, and the round hand's trials take three times the others'), two runs at once; its
    folder and its stderr (made before Chromium starts: playwright keeps an event loop in
    this thread)."""
    out, err = tmp_path_factory.mktemp("report"), io.StringIO()
    with contextlib.redirect_stderr(err):
        assert main(["report", "--url", server.ws, "--hands", "anthro,edged", "--tasks", "grasp",
                     "--grips", "spherical", "--seeds", "2", "--trials", "1", "--parallel", "2",
                     "--scene", f"report{id(out) % 10000}", "--out", str(out)]) == 0
    return out, err.getvalue()


def test_a_report_runs_every_hand_and_writes_every_trial(made):
    out, err = made
    # the finding: minutes with no output; a bar of runs with the time left
    assert "report: 100%" in err and "2/2" in err
    runs = json.loads((out / "runs.json").read_text())
    assert sorted((r["hand"], r["seed"]) for r in runs) == [("anthro", 2), ("edged", 2)]
    with (out / "trials.csv").open() as file:
        rows = list(csv.DictReader(file))
    assert len(rows) == 4  # 2 hands × light and heavy × 1 trial
    assert {r["weight"] for r in rows} == {"light", "heavy"} and all(float(r["massKg"]) > 0 for r in rows)
    assert json.loads((out / "trials.json").read_text())[0].keys() >= {"hand", "held", "slipFromContact"}


def test_the_report_page_plots_each_measure_per_hand(made, browser, tmp_path):  # noqa: F811
    out, _ = made
    page = browser.new_page(viewport={"width": 1200, "height": 800})
    try:
        page.goto((out / "report.html").as_uri())
        page.wait_for_selector("canvas")
        assert page.locator(".u-title").all_inner_texts() == [
            "grasp: held (share of trials)", "grasp: peak force on the object (median, N)",
            "grasp: slip from first contact (median, mm)"]
        legend = page.locator(".u-legend").first.inner_text()
        assert "anthro" in legend and "edged" in legend
        page.screenshot(path=str(tmp_path / "report.png"))
    finally:
        page.close()
    colours = Image.open(tmp_path / "report.png").convert("RGB").getcolors(1 << 24)
    # the first hand's bars (#1f77b4, drawn over white) fill part of the page: not blank
    assert sum(count for count, (r, g, b) in colours if b > 150 and r < 140 and g < 190) > 2000


def test_seeds_are_numbers_and_ranges():
    assert seeds("1-3,7") == [1, 2, 3, 7]
    with pytest.raises(Exception, match="numbers and ranges"):
        seeds("one")
