"""Processes the server starts end with it, kill -9 included: Linux's parent-death signal.

Every process the server starts is a child of its fork server, which ends when the
server's process does (it reads EOF on a pipe from the server); ``prctl(PR_SET_PDEATHSIG)``
then sends the child a signal, even while it is busy in one long call into C (PyBullet,
a mesh check), where a pipe's end is only noticed after it. No library wraps this one
call (``python-prctl`` is unmaintained), so ctypes calls the C library's ``prctl``.
"""

from __future__ import annotations

import ctypes
import os
import sys

PR_SET_PDEATHSIG = 1  # prctl(2)


def end_with_parent(signum: int) -> None:
    """Have ``signum`` sent to this process when its parent ends (at once if it already
    has: the parent may go before the signal is asked for)."""
    parent = os.getppid()
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None).prctl(PR_SET_PDEATHSIG, signum, 0, 0, 0)
    if os.getppid() != parent:
        os.kill(os.getpid(), signum)
