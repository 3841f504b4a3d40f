"""The FastAPI application: REST, the WebSocket endpoint and the scene hubs."""

from __future__ import annotations

import asyncio
import time
from contextlib import asynccontextmanager
from typing import AsyncIterator, Mapping

from fastapi import FastAPI, Request
from fastapi.responses import JSONResponse, Response
from starlette.exceptions import HTTPException as StarletteHTTPException

from ..core.limits import DEFAULT, Limits
from ..errors import LookupFailure, VPError
from . import heap, rest, socket
from .guard import LoopErrorLog
from .hub import DEFAULT_SCENE, Hubs, SceneSetup
from .pages import mount_pages

HTTP_CODES = {404: "not_found", 405: "method_not_allowed"}


def create_app(tick_rate: float = 60.0, setups: Mapping[str, SceneSetup] | None = None,
               limits: Limits = DEFAULT) -> FastAPI:
    """The server: the ``default`` scene exists from the start; ``setups`` prepare scenes
    by name (whenever one starts)."""
    hubs = Hubs(tick_rate, limits)
    for name, setup in (setups or {}).items():
        hubs.prepare(name, setup)

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        asyncio.get_running_loop().set_exception_handler(LoopErrorLog().handle)
        hubs.open(DEFAULT_SCENE)
        sweeper = asyncio.create_task(hubs.sweep())
        heap.settle()
        yield
        sweeper.cancel()
        await hubs.stop()

    app = FastAPI(title="Virtual Prosthetics", version=rest.VERSION, lifespan=lifespan)
    app.state.hubs = hubs
    app.state.started = time.monotonic()
    app.include_router(rest.router)
    app.include_router(socket.router)

    @app.exception_handler(VPError)
    async def vp_error(request: Request, error: VPError) -> JSONResponse:
        return rest.error_response(error, 404 if isinstance(error, LookupFailure) else 400)

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, error: StarletteHTTPException) -> Response:
        # every error body has the documented form, unmatched paths included
        code = HTTP_CODES.get(error.status_code, "http_error")
        return JSONResponse({"code": code, "message": str(error.detail)},
                            status_code=error.status_code, headers=error.headers)

    mount_pages(app)
    return app
