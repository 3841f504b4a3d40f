"""A scene's recent figures: percentiles, rates and CPU over the last window only."""

from __future__ import annotations

import pytest

from server.web.process.scene_metrics import SceneMetrics, percentile


def test_percentiles_are_nearest_ranks():
    ordered = [float(n) for n in range(1, 101)]
    assert percentile(ordered, 0.5) == 50 and percentile(ordered, 0.95) == 95
    assert percentile([7.0], 0.95) == 7


def test_a_busy_second_gives_tick_percentiles_and_rates():
    metrics = SceneMetrics()
    for n in range(1, 101):                       # 100 ticks in one second, 1 … 100 ms
        metrics.ticked(100 + n / 100, float(n), cpu=2 + n / 200)
        metrics.served(100 + n / 100, 3)
    figures = metrics.summary(now=101.0, cpu=2.5)
    assert (figures["tickMsP50"], figures["tickMsP95"], figures["tickMsMax"]) == (50, 95, 100)
    assert figures["tickMsLast"] == 100
    assert figures["ticksPerSecond"] == pytest.approx(100 / 0.99)
    assert figures["requestsPerSecond"] == pytest.approx(300 / 0.99)
    assert figures["cpuPercent"] == pytest.approx(100 * (2.5 - 2.005) / 0.99)
    assert (figures["ticks"], figures["requests"]) == (100, 300)


def test_old_ticks_leave_the_window_but_stay_in_the_totals():
    metrics = SceneMetrics(window=10)
    metrics.ticked(0, 500.0, cpu=0)              # a stall long ago
    for n in range(600):                          # then 60 quick ticks a second for 10 s
        metrics.ticked(5 + n / 60, 2.0, cpu=n / 600)
    figures = metrics.summary(now=15, cpu=1.0)
    assert figures["tickMsMax"] == 2 and figures["ticks"] == 601
    assert figures["ticksPerSecond"] == pytest.approx(60, rel=0.02)
    assert figures["windowSeconds"] == 10


def test_a_quiet_scene_reports_zeros_not_errors():
    figures = SceneMetrics().summary(now=50, cpu=0.25)
    assert figures["ticksPerSecond"] == figures["requestsPerSecond"] == figures["tickMsMax"] == 0
    assert figures["cpuSeconds"] == 0.25


def test_the_peak_force_is_the_most_in_the_window():
    metrics = SceneMetrics(window=10.0)
    metrics.ticked(1.0, 2.0, 0.0, force=50.0)
    metrics.ticked(2.0, 2.0, 0.0, force=20.0)
    metrics.ticked(3.0, 2.0, 0.0)
    assert metrics.summary(3.0, 0.0)["peakForceN"] == 50.0
    assert metrics.summary(11.5, 0.0)["peakForceN"] == 20.0  # the 50 N left the window
    assert metrics.summary(13.0, 0.0)["peakForceN"] == 0.0
