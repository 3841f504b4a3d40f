"""The FastAPI application: REST, the WebSocket endpoint and the scene hubs."""

from __future__ import annotations

import asyncio
import logging
import shutil
import tempfile
import time
from contextlib import asynccontextmanager
from pathlib import Path
from typing import AsyncIterator, Mapping, Protocol

from fastapi import Depends, FastAPI, Request
from fastapi.responses import JSONResponse, Response
from starlette.exceptions import HTTPException as StarletteHTTPException

from ...core.kit.limits import DEFAULT, Limits
from ...core.physics.assets import AssetLibrary
from ...core.kit.errors import (BusUnavailable, Forbidden, InternalError, LimitExceeded, LookupFailure,
                      RecordingBusy, RecordingDamaged, StorageFailure, TooLarge, VPError)
from . import assets, picture_route, recording_routes, rest, rest_base, robot_routes, socket
from ..process import heap
from .access import AccessPolicy, HostCheck, redact_tokens_in_logs, viewing_allowed
from .cors import PageOrigins
from ..connections.connection_limits import LoopErrorLog
from ..scenes.hub import DEFAULT_SCENE, Hubs, SceneSetup
from ..scenes.offload import CallerGone
from .api_docs import mount_api_docs
from .pages import mount_pages
from ..storage.state_dir import StateDir

HTTP_CODES = {404: "not_found", 405: "method_not_allowed"}
HTTP_STATUS: dict[type[VPError], int] = {LookupFailure: 404, Forbidden: 403, TooLarge: 413,
                                         LimitExceeded: 429, RecordingBusy: 409, StorageFailure: 507,
                                         RecordingDamaged: 422, BusUnavailable: 503}


class ClusterPart(Protocol):
    """This server's part in a cluster (:class:`server.cluster.roles.ClusterMember`)."""

    async def start(self, hubs: Hubs | None) -> None:
        """Join: ``hubs``' scenes run on the cluster's workers from now on."""

    async def stop(self) -> list[str]:
        """Leave; the scenes run here whose last changes could not be saved."""


def create_app(tick_rate: float = 60.0, setups: Mapping[str, SceneSetup] | None = None,
               limits: Limits = DEFAULT, uploads: Path | None = None,
               access: AccessPolicy = AccessPolicy(), state_dir: Path | None = None,
               cluster: ClusterPart | None = None) -> FastAPI:
    """The server: the ``default`` scene exists from the start; ``setups`` prepare scenes
    by name (whenever one starts). Uploaded meshes are kept in ``uploads`` (by default
    the state folder's, else a temporary folder removed when the server stops).
    ``access``: tokens, origins and host names. ``state_dir``: scenes are saved there and
    come back from there (:mod:`server.web.storage.state_dir`); after the server stopped,
    ``app.state.unsaved`` names the scenes whose last changes could not be saved.
    ``cluster``: scenes run on a cluster's workers instead of this server's processes."""
    state = StateDir(state_dir) if state_dir is not None else None
    temporary = uploads is None and state is None
    uploads = _upload_folder(uploads, state)
    hubs = Hubs(tick_rate, limits, AssetLibrary(uploads=uploads, limits=limits), state)
    for name, setup in (setups or {}).items():
        hubs.prepare(name, setup)

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        asyncio.get_running_loop().set_exception_handler(LoopErrorLog().handle)
        redact_tokens_in_logs()  # uvicorn has set its loggers up by now
        if cluster is not None:
            await cluster.start(hubs)
        hubs.open(DEFAULT_SCENE)  # saved scenes open when they are first used
        sweeper = asyncio.create_task(hubs.sweep())
        heap.settle()
        yield
        sweeper.cancel()
        app.state.unsaved = await hubs.stop()
        if cluster is not None:
            app.state.unsaved += await cluster.stop()
        if temporary:
            shutil.rmtree(uploads, ignore_errors=True)

    app = FastAPI(title="Virtual Prosthetics", version=rest.VERSION, lifespan=lifespan,
                  docs_url=None, redoc_url=None)  # api_docs: offline
    app.state.hubs = hubs
    app.state.unsaved = []  # scenes whose last changes could not be saved (the exit code)
    app.state.access = access
    app.state.started = time.monotonic()
    app.include_router(rest.router, dependencies=[Depends(viewing_allowed)])
    app.include_router(recording_routes.router, dependencies=[Depends(viewing_allowed)])
    app.include_router(assets.router, dependencies=[Depends(viewing_allowed)])
    app.include_router(robot_routes.router, dependencies=[Depends(viewing_allowed)])
    app.include_router(picture_route.router, dependencies=[Depends(viewing_allowed)])
    app.include_router(socket.router)
    _answer_errors(app)
    mount_pages(app)
    mount_api_docs(app)
    app.add_middleware(PageOrigins, policy=access)
    app.add_middleware(HostCheck, policy=access)  # outermost: a wrong Host gets nothing
    return app


def _upload_folder(uploads: Path | None, state: StateDir | None) -> Path:
    """Where uploads are kept: the given folder, the state folder's, or a temporary one."""
    if uploads is None:
        uploads = state.assets if state is not None else \
            Path(tempfile.mkdtemp(prefix="vp-uploads-"))
    try:
        uploads.mkdir(parents=True, exist_ok=True)
    except OSError as error:  # a state folder that cannot be written: reported there
        logging.getLogger(__name__).error("the upload folder %s cannot be made (%s)", uploads,
                                          error.strerror)
    return uploads


def _answer_errors(app: FastAPI) -> None:
    """Every error, expected or not, answered in the documented JSON form."""
    @app.exception_handler(VPError)
    async def vp_error(request: Request, error: VPError) -> JSONResponse:
        status = next((s for kind, s in HTTP_STATUS.items() if isinstance(error, kind)), 400)
        return rest_base.error_response(error, status)

    @app.exception_handler(CallerGone)
    async def caller_gone(request: Request, error: CallerGone) -> Response:
        return Response(status_code=499)  # (nobody reads it: nginx's "client closed request")

    @app.exception_handler(Exception)
    async def internal_error(request: Request, error: Exception) -> JSONResponse:
        # a bug: logged with its traceback by the server; the client gets the usual form
        return rest_base.error_response(InternalError("internal server error"), 500)

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, error: StarletteHTTPException) -> Response:
        # every error body has the documented form, unmatched paths included
        code = HTTP_CODES.get(error.status_code, "http_error")
        return JSONResponse({"code": code, "message": str(error.detail)},
                            status_code=error.status_code, headers=error.headers)
