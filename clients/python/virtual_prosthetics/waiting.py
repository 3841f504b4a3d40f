"""How long the client waits for the server: the scene's first snapshot, each answer a
script waits for, and every earlier write a read waits for.

One figure for all three, chosen by the user: ``connect(..., timeout=S)``,
``Session(timeout=S)``, the tasks CLI's ``--timeout S``, or ``VP_TIMEOUT=S`` in the
environment; otherwise :data:`DEFAULT_SECONDS`. A timeout is a guard against a server that
will never answer, not a budget: the default is long enough for a server whose two cores
are busy with a dozen scenes (a new scene's process then takes several seconds to start).
"""

from __future__ import annotations

import math
import os

DEFAULT_SECONDS = 60.0
ENVIRONMENT = "VP_TIMEOUT"


def wait_seconds(given: float | None = None) -> float:
    """The seconds to wait: ``given``, else ``VP_TIMEOUT``, else the default.

    ``math.inf`` waits for ever. A value that is not a positive number raises
    ``ValueError`` naming where it came from.
    """
    source = "timeout"
    if given is None:
        text = os.environ.get(ENVIRONMENT)
        if text is None or not text.strip():
            return DEFAULT_SECONDS
        source = ENVIRONMENT
        try:
            given = float(text)
        except ValueError:
            raise ValueError(f"{ENVIRONMENT} must be a number of seconds, got {text!r}") from None
    if isinstance(given, bool) or not isinstance(given, (int, float)) \
            or math.isnan(given) or given <= 0:
        raise ValueError(f"{source} must be a positive number of seconds, got {given!r}")
    return float(given)


def bound(seconds: float) -> float | None:
    """``seconds`` as the standard library's waits take it (``None``: for ever)."""
    return None if math.isinf(seconds) else seconds
