"""Fuzzers: protocol messages, REST operations, scene documents and glTF uploads.

Each is seeded, so a run repeats. The suite (``make test``) runs :data:`CASES` cases of
each, 500 by default; ``make test-long`` runs the full 10 000 (``VP_FUZZ_CASES``), as
CI does not: a fuzzer's outcome never depends on how fast the machine is, only on how
many cases it is given. (500, not the 1 000 it once was: the suite is CPU-bound on two
cores, and at a slow hour it crossed its 8 minutes; the fuzzers were a tenth of its CPU.)
"""

from __future__ import annotations

import os

CASES = int(os.environ.get("VP_FUZZ_CASES", "500"))
