"""The bench's live helpers: a measure starts on a server at rest."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

from bench.live import until_quiet

BUSY = """
import sys, time
from pathlib import Path
Path(sys.argv[1] + ".started").write_text("started")
end = time.process_time() + float(sys.argv[2])
while time.process_time() < end:  # a second of CPU, however long the machine takes
    pass
Path(sys.argv[1]).write_text("done")
time.sleep(60)
"""


def test_until_quiet_waits_for_a_busy_process_to_finish_its_work(tmp_path: Path) -> None:
    done = tmp_path / "done"
    busy = subprocess.Popen([sys.executable, "-c", BUSY, str(done), "1.0"])
    try:
        # (from its loop on: a loaded machine's interpreter, starting, could wait on the
        # disk longer than a window and look at rest)
        while not (tmp_path / "done.started").exists() and busy.poll() is None:
            time.sleep(0.01)
        until_quiet(lambda: [busy.pid])
        assert done.exists(), "until_quiet returned while the process was still working"
    finally:
        busy.kill()
        busy.wait()


def test_until_quiet_returns_at_once_for_processes_at_rest(tmp_path: Path) -> None:
    resting = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        assert until_quiet(lambda: [resting.pid]) < 30  # (one window, on any machine)
    finally:
        resting.kill()
        resting.wait()
