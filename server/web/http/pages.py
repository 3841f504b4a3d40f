"""The browser pages: the index, the viewer, the JavaScript client, npm dependencies, meshes.

three.js and lil-gui are served from ``clients/js/node_modules`` (installed from the npm registry
by the set-up command, never committed); the pages find them through an import map.
"""

from __future__ import annotations

import logging
from pathlib import Path

from fastapi import FastAPI
from fastapi.responses import FileResponse
from fastapi.staticfiles import StaticFiles

from ...core.physics.assets import BUNDLED_DIR, BUNDLED_URL
from .bare_imports import ModuleFiles

log = logging.getLogger(__name__)

WEB = Path(__file__).resolve().parents[3] / "web"
CLIENT = WEB.parent / "clients" / "js"
VENDOR = {name: CLIENT / "node_modules" / name
          for name in ("three", "lil-gui", "uplot", "swagger-ui-dist", "redoc")}


def mount_pages(app: FastAPI) -> None:
    """Add ``/``, ``/view`` and the static trees the pages load."""
    for name, folder in VENDOR.items():
        if not folder.is_dir():
            log.warning("%s is missing: run `make install` (the viewer needs it)", folder)
        app.mount(f"/vendor/{name}", ModuleFiles(directory=folder, check_dir=False),
                  name=f"vendor-{name}")
    app.mount("/web", ModuleFiles(directory=WEB / "src"), name="web")
    app.mount("/client", ModuleFiles(directory=CLIENT, check_dir=False), name="client")
    app.mount("/examples", StaticFiles(directory=WEB / "examples", html=True), name="examples")
    app.mount(BUNDLED_URL.rstrip("/"), StaticFiles(directory=BUNDLED_DIR), name="meshes")

    @app.get("/", include_in_schema=False)
    async def index() -> FileResponse:
        return FileResponse(WEB / "index.html")

    @app.get("/view", include_in_schema=False)
    async def view() -> FileResponse:
        return FileResponse(WEB / "view.html")
