"""The bench's live helpers: a measure starts on a server at rest."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from bench.live import until_quiet

BUSY = """
import sys, time
from pathlib import Path
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
