"""The fork server's processes never run the server's script again (forkserver_main.py)."""

import subprocess
import sys

from tests.conftest import ROOT

# a stand-in for vp-server's script: it imports server.cli, says each time it runs, and
# starts a process as the server starts a scene's; the process exits 1 if it has FastAPI
SCRIPT = """
from server.cli import main
print("ran", flush=True)
if __name__ == "__main__":
    from server.web.scenes.runner import CONTEXT
    child = CONTEXT.Process(target=exec, args=(
        "import sys; sys.exit(int('fastapi' in sys.modules or 'uvicorn' in sys.modules))",))
    child.start()
    child.join()
    print("child", child.exitcode, flush=True)
"""


def test_a_scenes_process_does_not_run_the_servers_script_or_load_the_web_process(tmp_path):
    # found: every scene's process ran vp-server's script again (multiprocessing's fix-up
    # of __main__), so the fork server preloaded FastAPI and uvicorn for it, 0.9 of a
    # CPU-second of every server's start before any scene
    script = tmp_path / "serve.py"
    script.write_text(SCRIPT)
    run = subprocess.run([sys.executable, str(script)], cwd=ROOT, capture_output=True,
                         text=True, timeout=120, env={"PYTHONPATH": str(ROOT)})
    assert run.stdout.split("\n") == ["ran", "child 0", ""], run.stderr[-2000:]


def test_a_server_started_by_a_process_that_has_the_fork_server_says_its_own_script(tmp_path):
    # the stand-in run by a process that imported the runner itself, as the suite and the
    # bench start servers: the variable it inherits names that process's script, not this
    script = tmp_path / "serve.py"
    script.write_text(SCRIPT)
    parent = ("import subprocess, sys, server.web.scenes.runner\n"
              f"sys.exit(subprocess.run([sys.executable, {str(script)!r}]).returncode)\n")
    run = subprocess.run([sys.executable, "-c", parent], cwd=ROOT, capture_output=True,
                         text=True, timeout=120, env={"PYTHONPATH": str(ROOT)})
    assert run.stdout.split("\n") == ["ran", "child 0", ""], run.stderr[-2000:]
