"""``report.html``: a page of bar charts to compare hands by (success per grip, peak
force, slip from first contact, relocations, drops, Box and Blocks), drawn by uPlot. The
page stands alone: uPlot's script and style are fetched from the server the report ran
on (it serves the npm package) and written into it."""

from __future__ import annotations

import html
import json
import statistics
import urllib.request
from typing import Any

UPLOT = ("/vendor/uplot/dist/uPlot.iife.min.js", "/vendor/uplot/dist/uPlot.min.css")
COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2"]


def charts(results: list[dict[str, Any]], rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Each chart: a title, its groups (x), one series per hand, a value per group."""
    hands = list(dict.fromkeys(run["hand"] for run in results))
    out = []
    grasp = [r for r in rows if r["task"] == "grasp"]
    if grasp:
        grips = list(dict.fromkeys(r["grip"] for r in grasp))
        for title, unit, value in (
                ("grasp: held (share of trials)", "share", lambda rs: statistics.mean(r["held"] for r in rs)),
                ("grasp: peak force on the object (median, N)", "N",
                 lambda rs: statistics.median(r["peakForceN"] for r in rs)),
                ("grasp: slip from first contact (median, mm)", "mm",
                 lambda rs: 1000 * statistics.median(r["slipFromContact"] for r in rs))):
            out.append(_chart(title, unit, grips, hands, grasp, "grip", value))
    for task, title, key in (("relocate", "relocate: brought to the target (share)", "success"),
                             ("hold", "hold: dropped (share)", "dropped")):
        picked = [r for r in rows if r["task"] == task]
        if picked:
            groups = list(dict.fromkeys(r.get("grip") or r.get("object") or task for r in picked))
            out.append(_chart(title, "share", groups, hands, picked,
                              "grip" if "grip" in picked[0] else None,
                              lambda rs, key=key: statistics.mean(bool(r[key]) for r in rs)))
    blocks = [r for r in rows if r["task"] == "box-and-blocks"]
    if blocks:
        out.append(_chart("Box and Blocks: blocks in 60 s (mean over seeds; adults 55-89)", "blocks",
                          ["blocks"], hands, blocks, None, lambda rs: statistics.mean(r["blocks"] for r in rs)))
    return out


def _chart(title: str, unit: str, groups: list[str], hands: list[str], rows: list[dict[str, Any]],
           by: str | None, value: Any) -> dict[str, Any]:
    def cell(group: str, hand: str) -> float | None:
        chosen = [r for r in rows if r["hand"] == hand and (by is None or r.get(by) == group)]
        return round(float(value(chosen)), 4) if chosen else None
    return {"title": title, "unit": unit, "groups": groups,
            "series": [{"hand": hand, "values": [cell(g, hand) for g in groups]} for hand in hands]}


def _fetch(server: str, path: str) -> str:
    with urllib.request.urlopen(server + path, timeout=30) as answer:  # our own server
        return answer.read().decode()


def page(results: list[dict[str, Any]], rows: list[dict[str, Any]], server: str) -> str:
    """The whole page: the charts' data, uPlot and the code that draws them."""
    script, style = (_fetch(server, path) for path in UPLOT)
    data = json.dumps({"charts": charts(results, rows), "colours": COLOURS})
    hands = ", ".join(html.escape(h) for h in dict.fromkeys(r["hand"] for r in results))
    return f"""<!doctype html>
<html><head><meta charset="utf-8"><title>Hand report</title>
<style>{style}
body {{ font: 14px system-ui, sans-serif; margin: 16px; }}
.charts {{ display: flex; flex-wrap: wrap; gap: 16px; }}
</style><script>{script}</script></head>
<body><h1>Hand-function report</h1>
<p>{len(results)} runs, {len(rows)} trials; hands: {hands}. Every trial is in trials.csv.</p>
<div class="charts" id="charts"></div>
<script>{DRAW}
draw({data});
</script></body></html>
"""


# Grouped bars: every hand's bar of a group at its own x (uPlot draws bars, not groups)
DRAW = """
function draw({charts, colours}) {
  const holder = document.getElementById('charts');
  for (const chart of charts) {
    const n = chart.series.length, stride = n + 1;
    const xs = [...Array(chart.groups.length * stride).keys()];
    const columns = chart.series.map((s, k) =>
      xs.map((x) => (x % stride === k ? s.values[Math.floor(x / stride)] : null)));
    const centres = chart.groups.map((_, g) => g * stride + (n - 1) / 2);
    const div = document.createElement('div');
    holder.append(div);
    new uPlot({
      title: chart.title, width: 560, height: 300,
      scales: { x: { time: false, range: [-1, xs.length - 1] }, y: { range: (u, lo, hi) => [0, Math.max(hi, 1e-9) * 1.1] } },
      axes: [{ splits: () => centres, values: () => chart.groups }, { label: chart.unit }],
      series: [{}, ...chart.series.map((s, k) => ({
        label: s.hand, stroke: colours[k % colours.length], fill: colours[k % colours.length] + 'aa',
        paths: uPlot.paths.bars({ size: [0.9, 40] }), points: { show: false } }))],
    }, [xs, ...columns], div);
  }
}
"""
