"""The FastAPI application: REST, the WebSocket endpoint and the scene hubs."""

from __future__ import annotations

import time
from contextlib import asynccontextmanager
from typing import AsyncIterator, Callable

from fastapi import FastAPI, Request
from fastapi.responses import JSONResponse

from ..core.scene import Scene
from ..errors import LookupFailure, VPError
from . import rest, socket
from .hub import Hubs
from .pages import mount_pages

SceneSetup = Callable[[Scene], Callable[[Scene, float], None] | None]

def create_app(tick_rate: float = 60.0, setup: SceneSetup | None = None) -> FastAPI:
    """The server: the ``default`` scene exists from the start (prepared by ``setup``)."""
    hubs = Hubs(tick_rate)

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        hub = hubs.open("default")
        if setup is not None:
            animator = setup(hub.scene)
            if animator is not None:
                hub.animators.append(animator)
        yield
        await hubs.stop()

    app = FastAPI(title="Virtual Prosthetics", version=rest.VERSION, lifespan=lifespan)
    app.state.hubs = hubs
    app.state.started = time.monotonic()
    app.include_router(rest.router)
    app.include_router(socket.router)

    @app.exception_handler(VPError)
    async def vp_error(request: Request, error: VPError) -> JSONResponse:
        return rest.error_response(error, 404 if isinstance(error, LookupFailure) else 400)

    mount_pages(app)
    return app
