"""Giving freed memory back to the system.

glibc keeps the memory Python frees (after a flood of messages, after a client's objects
are deleted) for reuse by the same process; ``malloc_trim`` returns it, so the server's
memory comes back to its baseline once the load is gone.
"""

from __future__ import annotations

import ctypes
import ctypes.util

try:
    _LIBC: ctypes.CDLL | None = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
    _LIBC.malloc_trim  # noqa: B018 (absent outside glibc)
except (OSError, AttributeError):
    _LIBC = None


def trim() -> None:
    """Return the process's free heap memory to the system (glibc; elsewhere nothing)."""
    if _LIBC is not None:
        _LIBC.malloc_trim(0)
