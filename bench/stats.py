"""A measured figure: the median and the 95th percentile of its samples."""

from __future__ import annotations

import statistics
from dataclasses import dataclass
from typing import Sequence


@dataclass(frozen=True)
class Figure:
    """Median and p95 (nearest rank) of ``count`` samples."""

    median: float
    p95: float
    count: int

    def as_dict(self) -> dict[str, float]:
        return {"median": self.median, "p95": self.p95, "count": self.count}


def figure(samples: Sequence[float]) -> Figure:
    """The figure of some samples (at least one)."""
    ordered = sorted(samples)
    rank = max(0, min(len(ordered) - 1, round(0.95 * len(ordered)) - 1))
    return Figure(statistics.median(ordered), ordered[rank], len(ordered))
