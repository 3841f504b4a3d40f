"""What a scene's process did lately, for ``/api/metrics``: tick durations (p50, p95, max),
ticks, requests and CPU per second, the peak contact force (dynamic mode), over a recent window rather than since start, so a
scene that was busy an hour ago does not look busy now and a fresh stall shows at once.

Pure bookkeeping with the clocks passed in, so tests need neither a process nor a wait.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

WINDOW_S = 10.0  # seconds of history the figures cover


def percentile(ordered: list[float], share: float) -> float:
    """The value below which ``share`` of ``ordered`` (sorted, not empty) lies (nearest rank)."""
    return ordered[min(len(ordered) - 1, max(0, round(share * len(ordered)) - 1))]


@dataclass
class SceneMetrics:
    """Ticks and requests of one scene, each noted with the wall time it happened."""

    window: float = WINDOW_S
    ticks: int = 0
    tick_failures: int = 0
    requests: int = 0
    _ticks: deque[tuple[float, float]] = field(default_factory=deque)     # (at, ms)
    _requests: deque[tuple[float, int]] = field(default_factory=deque)    # (at, count)
    _cpu: deque[tuple[float, float]] = field(default_factory=deque)       # (at, cpu seconds)
    _forces: deque[tuple[float, float]] = field(default_factory=deque)    # (at, newtons)

    def ticked(self, at: float, ms: float, cpu: float, force: float = 0.0) -> None:
        """A tick that ended at ``at`` took ``ms``; the process had used ``cpu`` seconds;
        the most force on any part was ``force`` newtons."""
        self.ticks += 1
        self._ticks.append((at, ms))
        self._cpu.append((at, cpu))
        if force:
            self._forces.append((at, force))
        self._forget(at)

    def served(self, at: float, count: int) -> None:
        """``count`` requests were answered at ``at``."""
        self.requests += count
        self._requests.append((at, count))
        self._forget(at)

    def summary(self, now: float, cpu: float) -> dict[str, float | int]:
        """The figures over the window ending ``now`` (tick times in milliseconds)."""
        self._forget(now)
        durations = sorted(ms for _, ms in self._ticks) or [0.0]
        span = self._span(now)
        first_cpu = self._cpu[0][1] if self._cpu else cpu
        return {"ticks": self.ticks, "tickFailures": self.tick_failures, "requests": self.requests,
                "windowSeconds": round(span, 3),
                "tickMsP50": percentile(durations, 0.5), "tickMsP95": percentile(durations, 0.95),
                "tickMsMax": durations[-1], "tickMsLast": self._ticks[-1][1] if self._ticks else 0.0,
                "ticksPerSecond": len(self._ticks) / span if span else 0.0,
                "requestsPerSecond": sum(n for _, n in self._requests) / span if span else 0.0,
                "cpuPercent": 100 * (cpu - first_cpu) / span if span else 0.0,
                "cpuSeconds": cpu, "peakForceN": max((f for _, f in self._forces), default=0.0)}

    def _span(self, now: float) -> float:
        """How much of the window has history (a young scene has less than all of it)."""
        oldest = min([d[0][0] for d in (self._ticks, self._requests) if d], default=now)
        return min(self.window, now - oldest)

    def _forget(self, now: float) -> None:
        for noted in (self._ticks, self._requests, self._cpu, self._forces):
            while noted and noted[0][0] < now - self.window:
                noted.popleft()
