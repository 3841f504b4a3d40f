"""How many cores a set of processes uses: their user and system time from ``/proc``,
between two looks (Linux), and what they are expected to use."""

from __future__ import annotations

import os
import time
from pathlib import Path

TICKS = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid: int) -> float:
    """A process's user and system CPU seconds so far (0 once it is gone)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return 0.0
    return (int(fields[11]) + int(fields[12])) / TICKS


class ProcessCpu:
    """The cores each of some processes used between the last two looks (only those seen
    at both: a share measured over a whole look), and what a set of them is expected to use."""

    def __init__(self) -> None:
        self.shares: dict[int, float] = {}  # pid -> cores, over the last whole look
        self._seconds: dict[int, float] = {}
        self._when = time.monotonic()

    def measure(self, pids: list[int]) -> None:
        """Look again at these processes."""
        now = time.monotonic()
        span = max(now - self._when, 1e-3)
        seconds = {pid: cpu_seconds(pid) for pid in pids}
        self.shares = {pid: max(0.0, s - self._seconds[pid]) / span
                       for pid, s in seconds.items() if pid in self._seconds}
        self._seconds, self._when = seconds, now

    def expected(self, pids: list[int | None], least: float,
                 typical: list[int] | None = None) -> float:
        """The cores these processes are expected to use: each measured one its share; one
        not measured over a whole look yet (new, or not started: None) the mean share of
        the measured ones of ``typical`` (default: ``pids``), and at least ``least``.
        (Counting only what was measured let a burst of new processes within one look pass
        any bound.)"""
        known = [self.shares[pid] for pid in pids if pid is not None and pid in self.shares]
        like = known if typical is None else [self.shares[p] for p in typical if p in self.shares]
        guess = max(sum(like) / len(like), least) if like else least
        return sum(known) + guess * (len(pids) - len(known))
