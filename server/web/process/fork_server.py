"""The fork server that starts scene processes, made as a fork of the server's own process.

Scene processes start from multiprocessing's fork server (runner.py's ``CONTEXT``), which
multiprocessing starts as a new interpreter that imports the scene code again: 0.6-0.8
CPU-seconds of every server's start, for modules the server's process has already
imported. :func:`fork_here` starts the same fork server as a fork of this process instead,
in a few milliseconds.

multiprocessing offers no way to start its fork server but a new interpreter
(``ForkServer.ensure_running``), so this does what that does, with ``os.fork`` in place of
the new interpreter: the same listening socket and "alive" pipe handed to
``forkserver.main``, and the same three attributes ``ensure_running`` sets and checks
afterwards (it then finds the fork server running, and starts a new one the usual way
should it die). A fork is only safe while this process has one thread (a lock another
thread held stays held in the child), so with more it does nothing and multiprocessing
starts its own when the first scene needs it.
"""

from __future__ import annotations

import gc
import importlib
import os
import socket
import threading
import traceback
from multiprocessing import connection, forkserver, resource_tracker, util
from typing import NoReturn, Sequence


def fork_here(preload: Sequence[str]) -> bool:
    """Start the fork server as a fork of this process, importing ``preload`` in it first
    (whichever of them this process has not imported: the last freezes the heap); False
    when it cannot (threads running, or a fork server already started)."""
    server = forkserver._forkserver  # type: ignore[attr-defined]
    if threading.active_count() > 1 or server._forkserver_pid is not None:
        return False
    resource_tracker.ensure_running()  # (as ensure_running does first: children share it)
    with socket.socket(socket.AF_UNIX) as listener:
        address = connection.arbitrary_address("AF_UNIX")  # type: ignore[attr-defined]
        listener.bind(address)
        if not util.is_abstract_socket_namespace(address):
            os.chmod(address, 0o600)
        listener.listen()
        alive_r, alive_w = os.pipe()
        # collected and frozen before the fork: a collection in the child (its heap module's)
        # would write to every object it walks, copying the pages it shares with this process
        gc.collect()
        gc.freeze()
        pid = os.fork()
        if pid == 0:
            _serve(listener.fileno(), alive_r, alive_w, preload)
        os.close(alive_r)
    server._forkserver_address = address
    server._forkserver_alive_fd = alive_w
    server._forkserver_pid = pid
    return True


def _serve(listener: int, alive_r: int, alive_w: int, preload: Sequence[str]) -> NoReturn:
    """The child: serve as the fork server until the server's process and its scenes are
    gone (the alive pipe's end), then exit without the parent's exit handlers."""
    code = 0
    try:
        os.close(alive_w)
        for name in preload:
            importlib.import_module(name)
        forkserver.main(listener, alive_r, [])
    except SystemExit as ending:  # (forkserver.main's way to end)
        code = ending.code if isinstance(ending.code, int) else 0
    except BaseException:
        traceback.print_exc()
        code = 1
    finally:
        os._exit(code)
