"""The process's heap: freed memory given back, long-lived objects kept out of collections.

glibc keeps the memory Python frees (after a flood of messages, after a client's objects
are deleted) for reuse by the same process; ``malloc_trim`` returns it, so the server's
memory comes back to its baseline once the load is gone.

Python's full collection walks every tracked object while holding the GIL: in the server's
process, with FastAPI, pydantic and the schema loaded (about 60 000 objects), one took 50 ms
under load, long enough for every viewer of every scene to miss three frames.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import gc

try:
    _LIBC: ctypes.CDLL | None = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
    _LIBC.malloc_trim  # noqa: B018 (absent outside glibc)
except (OSError, AttributeError):
    _LIBC = None


def trim() -> None:
    """Return the process's free heap memory to the system (glibc; elsewhere nothing)."""
    if _LIBC is not None:
        _LIBC.malloc_trim(0)


def settle() -> None:
    """Keep every object made so far (modules, app, schema) out of later collections.

    Called once start-up is over; collections then walk only what was made since, so
    their pauses stay proportional to the live load, not to the libraries loaded.
    """
    gc.collect()
    gc.freeze()
