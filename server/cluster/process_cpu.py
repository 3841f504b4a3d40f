"""How many cores a set of processes uses: their user and system time from ``/proc``,
between two looks (Linux)."""

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
    """The cores some processes used since the last look (a process new since then counts
    from its start)."""

    def __init__(self) -> None:
        self.cores_used = 0.0
        self._seconds: dict[int, float] = {}
        self._when = time.monotonic()

    def measure(self, pids: list[int]) -> float:
        now = time.monotonic()
        seconds = {pid: cpu_seconds(pid) for pid in pids}
        used = sum(s - self._seconds.get(pid, 0.0) for pid, s in seconds.items())
        self.cores_used = max(0.0, used) / max(now - self._when, 1e-3)
        self._seconds, self._when = seconds, now
        return self.cores_used
