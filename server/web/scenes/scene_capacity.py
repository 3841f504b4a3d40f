"""How many scenes this machine holds: the default of the ``scenes`` limit.

A scene nobody uses stops ticking (server.web.process.worker), so what it costs is memory: its
process's private pages, 69 MB measured (bench/idle_scenes.py: proportional set size of
idle scene processes; 27 MB of it is PyBullet's own client). A busy scene costs a core
besides, but CPU is shared fairly by the system, while memory that runs out stalls every
scene at once. So the default is what a share of the machine's memory holds.
"""

from __future__ import annotations

from pathlib import Path

SCENE_BYTES = 70 << 20   # one idle scene's process (measured, rounded up)
MEMORY_SHARE = 0.6       # of the machine's memory, for scenes (the rest: server, system, peaks)
FEWEST, MOST = 10, 1_000  # whatever the machine says


def scenes_held(memory_bytes: int | None) -> int:
    """Scenes that fit ``memory_bytes`` (None, unknown: the fewest)."""
    if memory_bytes is None:
        return FEWEST
    return max(FEWEST, min(MOST, int(memory_bytes * MEMORY_SHARE) // SCENE_BYTES))


def machine_memory(proc: Path = Path("/proc"), cgroup: Path = Path("/sys/fs/cgroup")) -> int | None:
    """The memory this process may use: the machine's, or its container's when smaller."""
    total = None
    try:
        for line in (proc / "meminfo").read_text().splitlines():
            if line.startswith("MemTotal:"):
                total = int(line.split()[1]) * 1024
    except OSError:
        return None
    try:
        bound = (cgroup / "memory.max").read_text().strip()
    except OSError:
        bound = "max"
    if total is not None and bound.isdigit():
        total = min(total, int(bound))
    return total
