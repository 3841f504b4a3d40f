"""The JavaScript client's own tests (node:test), run as part of the one test command."""

from __future__ import annotations

import subprocess
from pathlib import Path

CLIENT = Path(__file__).resolve().parents[3] / "clients" / "js"


def test_the_javascript_client_tests_pass():
    result = subprocess.run(["node", "--test", "test/"], cwd=CLIENT, capture_output=True,
                            text=True, timeout=300)
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert "# fail 0" in result.stdout and "# pass 0" not in result.stdout
