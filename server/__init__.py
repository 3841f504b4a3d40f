"""The Virtual Prosthetics server: ``core`` (the simulation, sans-I/O) and ``web`` (its adapter)."""

import os

# Every scene is one process doing small array operations a tick; OpenBLAS's own threads
# only spin beside it (15 % more CPU for the same sensing, and slower) on machines whose
# cores the scenes already share. Set before numpy is first imported; a caller's own
# choice stands.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
