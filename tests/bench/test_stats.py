"""A figure's median and 95th percentile (nearest rank)."""

from bench.stats import figure


def test_median_and_nearest_rank_p95():
    found = figure([float(v) for v in range(100, 0, -1)])  # 1 … 100, unordered
    assert (found.median, found.p95, found.count) == (50.5, 95.0, 100)
    assert figure([7.0]).as_dict() == {"median": 7.0, "p95": 7.0, "count": 1}
