"""The fork server's heap, frozen before any scene is forked: a scene's collections never
walk (and so never copy) the objects it shares with the fork server."""

import subprocess
import sys

from tests.conftest import ROOT

FROZEN = """
import gc
import server.web.process.worker  # what the fork server preloads (runner.py)
loaded = len(gc.get_objects())
import server.web.process.forkserver_heap
print(loaded, gc.get_freeze_count(), len(gc.get_objects()))
"""


def test_importing_it_freezes_everything_loaded_before():
    loaded, frozen, walked = map(int, subprocess.run(
        [sys.executable, "-c", FROZEN], cwd=ROOT, capture_output=True, text=True,
        check=True).stdout.split())
    assert frozen >= loaded * 0.9  # (a collection first: garbage is not kept)
    assert walked < loaded * 0.05  # what a scene's collection would still walk
