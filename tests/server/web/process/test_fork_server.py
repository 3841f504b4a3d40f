"""The fork server made as a fork of the server's process (fork_server.py): scenes start
from it as from multiprocessing's own, which starts only when a fork is not safe."""

import json
import os
import subprocess
import sys
from pathlib import Path

from tests.conftest import ROOT, descendants, eventually, start_server, stop_server

# Starts the fork server (threads first, when asked), then a process as a scene's starts;
# the process prints what it found and who its parent is, then the script who it is.
SCRIPT = '''
import json, os, sys, threading
from multiprocessing import forkserver
from server.web.scenes.runner import CONTEXT, start_fork_server

REPORT = """import gc, json, os, sys
print(json.dumps({"parent": os.getppid(), "frozen": gc.get_freeze_count(),
                  "spatial": "scipy.spatial" in sys.modules}), flush=True)"""

if __name__ == "__main__":
    if sys.argv[1] == "threads":
        threading.Thread(target=threading.Event().wait, daemon=True).start()
    forked = start_fork_server()
    child = CONTEXT.Process(target=exec, args=(REPORT,))
    child.start()
    child.join()
    print(json.dumps({"forked": forked, "code": child.exitcode,
                      "server": forkserver._forkserver._forkserver_pid}), flush=True)
'''


def _run(tmp_path: Path, mode: str) -> dict:
    script = tmp_path / "start.py"
    script.write_text(SCRIPT)
    run = subprocess.run([sys.executable, str(script), mode], cwd=ROOT, capture_output=True,
                         text=True, timeout=120, env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert run.returncode == 0, run.stderr[-2000:]
    child, parent = map(json.loads, run.stdout.splitlines())
    assert parent["code"] == 0
    return {**child, **parent}


def _command(pid: int) -> list[str]:
    return Path(f"/proc/{pid}/cmdline").read_bytes().decode().split("\0")[:-1]


def _parent(pid: int) -> int:
    return int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])


def test_a_process_starts_from_a_fork_server_forked_from_this_process(tmp_path):
    found = _run(tmp_path, "alone")
    assert found["forked"] is True
    assert found["parent"] == found["server"]  # started by the fork server, as before
    assert found["frozen"] > 10_000  # the heap it shares stays out of its collections
    assert found["spatial"]  # what the fork server preloads, imported in the fork
    eventually(lambda: not Path(f"/proc/{found['server']}").exists())  # it ends with its parent


def test_with_threads_running_multiprocessings_own_fork_server_starts_instead(tmp_path):
    found = _run(tmp_path, "threads")
    assert found["forked"] is False
    assert found["parent"] == found["server"]
    assert found["frozen"] > 10_000 and found["spatial"]  # its preload list, as before


def test_a_servers_scenes_run_in_forks_of_the_server_itself():
    # found: each server's start paid 0.6-0.8 CPU-s for a new interpreter, the fork
    # server, importing the scene code the server's process had already imported
    running = start_server("--no-demo")
    try:
        server = running.process.pid
        eventually(lambda: running.get("/api/metrics")["scenes"]["default"]["state"] == "running")
        scene = running.get("/api/metrics")["scenes"]["default"]["pid"]
        fork_server = _parent(scene)
        assert _parent(fork_server) == server
        assert _command(fork_server) == _command(server)  # a fork: no interpreter of its own
        assert not any("multiprocessing.forkserver" in " ".join(_command(pid))
                       for pid in descendants(server))
    finally:
        stop_server(running)
