"""A process that asked for its parent's death signal ends when its parent is killed."""

import os
import signal
import subprocess
import sys
from pathlib import Path

from tests.conftest import ROOT, WAIT_SECONDS, eventually

CHILD = """
import signal, time
from server.web.process.parent_death import end_with_parent
end_with_parent(signal.SIGKILL)
print("ready", flush=True)
time.sleep(600)
"""
PARENT = f"""
import subprocess, sys, time
child = subprocess.Popen([sys.executable, "-c", {CHILD!r}], stdout=subprocess.PIPE, text=True)
child.stdout.readline()
print(child.pid, flush=True)
time.sleep(600)
"""


def test_a_child_that_asked_ends_when_its_parent_is_killed_9():
    parent = subprocess.Popen([sys.executable, "-c", PARENT], cwd=ROOT, stdout=subprocess.PIPE,
                              text=True)
    child = int(parent.stdout.readline())
    assert Path(f"/proc/{child}").exists()
    os.kill(parent.pid, signal.SIGKILL)
    parent.wait(timeout=WAIT_SECONDS)
    eventually(lambda: not Path(f"/proc/{child}").exists() or
               Path(f"/proc/{child}/stat").read_text().split(") ")[1][0] == "Z")
