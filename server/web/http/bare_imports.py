"""ES modules served with their bare imports resolved (``'three'`` → ``/vendor/three/…``).

A 1.0 page has no import map: it only imports ``/client/virtual-prosthetics.js``. That
module, the viewer and three.js's add-ons import ``three``, ``lil-gui`` and ``uplot`` by name, so the
server rewrites those names in the JavaScript it serves, once per file version. The map
is the one place that says where each package lives.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

from starlette.datastructures import Headers
from starlette.responses import Response
from starlette.staticfiles import StaticFiles
from starlette.types import Scope

IMPORT_MAP = {
    "three": "/vendor/three/build/three.module.js",
    "three/addons/": "/vendor/three/examples/jsm/",
    "lil-gui": "/vendor/lil-gui/dist/lil-gui.esm.js",
    "uplot": "/vendor/uplot/dist/uPlot.esm.js",
}
_BARE = re.compile(r"""(\bfrom\s*|\bimport\s*\(\s*|\bimport\s+)(['"])(three(?:/addons/[^'"]*)?|lil-gui|uplot)\2""")


def resolve(specifier: str) -> str:
    """Where a bare specifier points."""
    if specifier in IMPORT_MAP:
        return IMPORT_MAP[specifier]
    return IMPORT_MAP["three/addons/"] + specifier.removeprefix("three/addons/")


def rewrite(source: str) -> str:
    """``source`` with every bare import of three, its add-ons, lil-gui and uPlot resolved."""
    return _BARE.sub(lambda m: f"{m[1]}{m[2]}{resolve(m[3])}{m[2]}", source)


class ModuleFiles(StaticFiles):
    """Static files whose ``.js`` files come with bare imports resolved (cached)."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._cache: dict[str, tuple[float, bytes]] = {}

    def file_response(self, full_path: str | os.PathLike[str], stat_result: os.stat_result,
                      scope: Scope, status_code: int = 200) -> Response:
        path = str(full_path)
        if not path.endswith((".js", ".mjs")):
            return super().file_response(full_path, stat_result, scope, status_code)
        cached = self._cache.get(path)
        if cached is None or cached[0] != stat_result.st_mtime:
            body = rewrite(Path(path).read_text(encoding="utf-8")).encode()
            cached = self._cache[path] = (stat_result.st_mtime, body)
        etag = f'"{stat_result.st_mtime_ns:x}-{len(cached[1]):x}"'
        # a 1.0 page may live elsewhere and import the client from here (module scripts
        # are fetched with CORS)
        headers = {"cache-control": "no-cache", "etag": etag, "access-control-allow-origin": "*"}
        if etag in Headers(scope=scope).get("if-none-match", ""):
            return Response(status_code=304, headers=headers)
        return Response(cached[1], status_code, media_type="text/javascript", headers=headers)
