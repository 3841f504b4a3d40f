"""The processes below others: a server's scene processes (the forkserver's children), a
cluster's workers' scenes."""

from __future__ import annotations

from pathlib import Path


def descendants(*pids: int) -> list[int]:
    """Every process below these (from each process's parent in ``/proc``)."""
    children: dict[int, list[int]] = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            parent = int(stat.read_text().rsplit(")", 1)[1].split()[1])
        except (OSError, IndexError, ValueError):
            continue  # gone meanwhile
        children.setdefault(parent, []).append(int(stat.parent.name))
    found, level = [], list(pids)
    while level:
        level = [child for parent in level for child in children.get(parent, [])]
        found += level
    return found
