"""Robots from files over HTTP: ``POST /api/robots`` reads and keeps one (a client then
makes ``ImportedRobot(file)``), ``POST /api/scenes/{scene}/robots`` also places it.

The body is read within ``robotBytes`` and parsed in the checking process
(:mod:`server.web.scenes.offload`), so a large robot never holds up the event loop or a scene;
what a file makes (link meshes, the description) is kept as uploads are, by content hash.
"""

from __future__ import annotations

import json
import math
from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse

from ...core.physics.robot_upload import store_robot_upload
from ...core.kit.errors import BadArguments
from ..process.messages import Place
from .access import changing_allowed
from .rest_base import NOT_FOUND, ErrorBody, hub_of, read_body

router = APIRouter(prefix="/api")
REFUSED: dict[int | str, dict[str, Any]] = {
    400: {"model": ErrorBody, "description": "Not a robot this server reads (bad_asset), naming "
                                             "what is wrong: a joint, a mesh, a path"},
    403: {"model": ErrorBody, "description": "A path that leaves the upload, or no token (forbidden)"},
    413: {"model": ErrorBody, "description": "Larger than the robotBytes limit (too_large)"},
    429: {"model": ErrorBody, "description": "Too many files or triangles (limit_exceeded)"}}
BODY = {"requestBody": {"required": True, "description": "a zip of the description and its "
                        "meshes, or a bare .urdf or MJCF .xml", "content": {
    media: {"schema": {"type": "string", "format": "binary"}}
    for media in ("application/zip", "application/xml", "application/octet-stream")}}}


async def _stored(request: Request, file: str | None) -> dict[str, Any]:
    changing_allowed(request)
    hubs = request.app.state.hubs
    data = await read_body(request, hubs.limits.robot_bytes, "robotBytes", "the robot")
    return await hubs.offload.run(store_robot_upload, hubs.uploads, data, file, hubs.limits)


@router.post("/robots", status_code=201, responses=REFUSED, openapi_extra=BODY,
             summary="Read a robot file (URDF, or a zip with its meshes) and keep it")
async def upload_robot(request: Request, file: str | None = None) -> JSONResponse:
    """The answer: ``file`` (give it to ``ImportedRobot``), the robot's ``name``, its
    ``links`` and its ``motors`` (``name``, ``min``, ``max``, ``follows``) in motor order.
    ``?file=PATH``: the description inside a zip that holds several."""
    return JSONResponse(await _stored(request, file), status_code=201)


@router.post("/scenes/{scene}/robots", status_code=201, responses={**REFUSED, **NOT_FOUND},
             openapi_extra=BODY, summary="Read a robot file and place the robot in a scene")
async def place_robot(request: Request, scene: str, file: str | None = None,
                      position: str = "0,0,0", rotation: str = "0,0,0,1") -> JSONResponse:
    """The robot is the server's (``api.<k>``), shared (anyone may steer it) and kept; the
    answer is its report (``GET …/robots/{id}``: ``id``, ``name``, motors with ``id``,
    ``name``, ``min``, ``max``), with ``file``. ``position``: ``x,y,z``; ``rotation``: a
    quaternion ``x,y,z,w``."""
    pose = _numbers(position, 3, "position"), _numbers(rotation, 4, "rotation")
    hub = hub_of(request, scene)
    stored = await _stored(request, file)
    report = json.loads(await hub.runner.call(Place(stored["file"], *pose)))
    return JSONResponse({**report, "file": stored["file"]}, status_code=201)


def _numbers(text: str, count: int, name: str) -> tuple[float, ...]:
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != count or not all(math.isfinite(v) and abs(v) <= 1e5 for v in values):
        raise BadArguments(f"?{name}= takes {count} finite numbers separated by commas, got {text!r}")
    if count == 4:
        norm = math.sqrt(sum(v * v for v in values))
        if norm < 1e-9:
            raise BadArguments(f"?{name}= is a quaternion x,y,z,w of some length, got {text!r}")
        values = tuple(v / norm for v in values)
    return values
