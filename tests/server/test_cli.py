"""``vp-server``'s module: what starting a server costs before it serves."""

from __future__ import annotations

import subprocess
import sys

from tests.conftest import ROOT


def test_the_web_process_starts_without_the_mesh_libraries():
    # trimesh and scipy are half a second of every start, Pillow a sixth; only a scene's
    # process (whose fork server preloads scipy) and a file export use them
    loaded = subprocess.run(
        [sys.executable, "-c", "import sys, server.cli\n"
         "print(sorted(m for m in ('trimesh', 'scipy', 'PIL') if m in sys.modules))"],
        cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip()
    assert loaded == "[]"
