"""What the repository writes from its sources of truth, and nothing else: ``make generate``
(``python -m generate``) writes it all, and ``tests/generate/test_generated.py`` fails when
a written file drifts from what its generator makes now.

Each module is one generator with ``outputs()``, the files it writes and their contents:

- :mod:`.api_table`: ``protocol/api.json`` from the API table (``server/core/protocol/api.py``)
- :mod:`.message_types`: the typed wire messages of the server, the Python client and the
  JavaScript client, from ``protocol/schema/protocol.json``
- :mod:`.skeletons`: ``clients/js/skeletons.js``, the nodes of every hand, from the server's hands
- :mod:`.meshes`: ``assets/gltf/*.glb``, the round and anthropomorphic hands' meshes

Generators import the server; the server never imports them (they are tooling, not runtime).
"""

from __future__ import annotations

from pathlib import Path
from types import ModuleType

from . import api_table, meshes, message_types, skeletons

GENERATORS: tuple[ModuleType, ...] = (api_table, message_types, skeletons, meshes)


def outputs() -> dict[Path, str | bytes]:
    """Every generated file and what it should hold."""
    return {path: content for generator in GENERATORS for path, content in generator.outputs().items()}
