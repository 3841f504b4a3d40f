"""Imported first by the fork server that starts scene processes (runner.py's preload list):
its processes never run the server's script again.

Every process multiprocessing starts runs the parent's ``__main__`` script again (its fix-up
of ``__main__``), unless the ``__main__`` it starts with already has that script's path as
its ``__file__``. vp-server's script imports server.cli, so a scene's process imported
FastAPI and uvicorn anew (0.33 CPU-seconds of its start), or the fork server preloaded them
for every server start (0.9 CPU-seconds, paid before any scene). No scene needs the
script: the fork server's ``__main__`` is given its path (MAIN_PATH, set by runner.py
before the fork server starts), and what it forks inherits that. (vp-server itself forks
its fork server, :mod:`.fork_server`, which has the script already; this is for the fork
server multiprocessing starts where a fork is not safe.)
"""

import os
import sys

MAIN_PATH = "VP_FORKSERVER_MAIN"  # the environment variable

if os.environ.get(MAIN_PATH):
    sys.modules["__main__"].__file__ = os.environ[MAIN_PATH]
