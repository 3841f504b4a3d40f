"""Fuzzers: protocol messages, REST operations, scene documents and glTF uploads.

Each is seeded, so a run repeats. The suite (``make test``) runs :data:`CASES` cases of
each, 1 000 by default; ``make test-long`` runs the full 10 000 (``VP_FUZZ_CASES``), as
CI does not: a fuzzer's outcome never depends on how fast the machine is, only on how
many cases it is given.
"""

from __future__ import annotations

import os

CASES = int(os.environ.get("VP_FUZZ_CASES", "1000"))
