"""What every REST route module shares: the error body (and its OpenAPI entry), the scene
a path names, and a request body read up to a limit."""

from __future__ import annotations

from typing import Any

from fastapi import Request
from fastapi.responses import JSONResponse
from pydantic import BaseModel

from ...core.kit.errors import TooLarge, UnknownScene, VPError
from ..scenes.hub import Hubs
from ..scenes.scene_hub import SceneHub


class ErrorBody(BaseModel):
    """What a refused REST request gets: the same code and message as on the WebSocket."""

    code: str
    message: str
    details: dict[str, Any] | None = None


NOT_FOUND: dict[int | str, dict[str, Any]] = {
    404: {"model": ErrorBody, "description": "No such scene (or robot, sensor, object)"}}
def error_response(error: VPError, status: int) -> JSONResponse:
    """A structured error body: the same code and message as on the WebSocket."""
    wire = error.to_wire()
    body = {"code": wire["code"], "message": wire["message"]}
    if error.details:
        body["details"] = wire["details"]
    return JSONResponse(body, status_code=status)


def hubs_of(request: Request) -> Hubs:
    """The server's scenes (and recordings), as the app keeps them."""
    return request.app.state.hubs


def hub_of(request: Request, scene: str) -> SceneHub:
    """A running scene's hub; a saved scene that is not running starts (from its file), as
    does one whose process failed (a cluster's worker died) with nobody there to restart it."""
    hubs = hubs_of(request)
    hub = hubs.get(scene)
    if (hub is None or hub.ended and hub.stored) and hubs.state is not None and \
            scene in hubs.state.saved_scenes():
        hub = hubs.open(scene)
    if hub is None:
        raise UnknownScene(f"no scene named {scene[:80]!r}", scene=scene)
    return hub


async def read_body(request: Request, limit: int, name: str, what: str) -> bytes:
    """A request's body, refused (``too_large``, naming the limit) past ``limit`` bytes
    without reading the rest."""
    data = bytearray()
    async for chunk in request.stream():
        data += chunk
        if len(data) > limit:
            raise TooLarge(f"{what} has more than {limit} bytes, the most taken", limit=name,
                           value=limit)
    return bytes(data)
