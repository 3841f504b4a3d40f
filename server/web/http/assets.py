"""Mesh files over HTTP: ``POST /api/assets`` takes an upload, ``GET`` lists and serves them.

Uploads are checked (size, layout, what they expand to, indices, then read) in the checking
process (:mod:`server.web.scenes.offload`), so no file holds the event loop or its memory, and
kept under the hash of their bytes
(:meth:`server.web.storage.upload_folder.UploadFolder.store`). Scenes read them by that name:
``GLTFPart('<hash>.glb')``. When the folder holds as many files as the ``assets`` limit
allows, an upload first removes those that no scene (running or saved) is made of and
that were not uploaded in the last hour; the folder is the server's own.
"""

from __future__ import annotations

import asyncio
import logging
import time
from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import FileResponse, JSONResponse

from ...core.physics.assets import AssetLibrary, plain_name
from ...core.kit.errors import LimitExceeded, UnknownAsset
from .access import changing_allowed
from .rest_base import NOT_FOUND, ErrorBody, read_body

log = logging.getLogger(__name__)
router = APIRouter(prefix="/api")
KEEP_SECONDS = 3600  # an unused upload younger than this stays: its script may be about to use it
MEDIA_TYPES = {"glb": "model/gltf-binary", "gltf": "model/gltf+json", "robot": "application/json"}
REFUSED: dict[int | str, dict[str, Any]] = {
    400: {"model": ErrorBody, "description": "Not a usable glTF mesh (bad_asset)"},
    403: {"model": ErrorBody, "description": "The server's token was not given (forbidden)"},
    413: {"model": ErrorBody, "description": "Larger than the assetBytes limit (too_large)"},
    429: {"model": ErrorBody, "description": "Too many triangles or files (limit_exceeded)"}}


def _library(request: Request) -> AssetLibrary:
    return request.app.state.hubs.assets


UPLOAD_BODY = {"requestBody": {"required": True, "description": "the file's bytes", "content": {
    media: {"schema": {"type": "string", "format": "binary"}}
    for media in ("model/gltf-binary", "model/gltf+json", "application/octet-stream")}}}


@router.post("/assets", status_code=201, responses=REFUSED, openapi_extra=UPLOAD_BODY,
             summary="Upload a glTF mesh (GLB, or glTF with embedded buffers) as the body")
async def upload(request: Request) -> JSONResponse:
    """The body is the file. The answer names it: ``{"name", "url", "bytes", "triangles"}``;
    give ``name`` to ``GLTFPart`` (or ``RoundFinger``…) in any scene. With a server token,
    ``Authorization: Bearer <token>`` is needed."""
    changing_allowed(request)
    hubs = request.app.state.hubs
    data = await read_body(request, hubs.limits.asset_bytes, "assetBytes", "the file")
    try:
        stored = await hubs.offload.run(hubs.uploads.store, data, hubs.limits)
    except LimitExceeded as full:
        if full.details.get("limit") != "assets":
            raise
        in_use = await hubs.uploads_in_use()
        removed = await asyncio.to_thread(hubs.uploads.collect, in_use,
                                          time.time() - KEEP_SECONDS)
        if not removed:
            raise LimitExceeded(f"{full.message}, each used by a scene or uploaded in the "
                                f"last {KEEP_SECONDS // 60} minutes", **full.details) from None
        log.info("%d uploaded files no scene used were removed to make room", len(removed))
        stored = await hubs.offload.run(hubs.uploads.store, data, hubs.limits)
    return JSONResponse(stored, status_code=201)


@router.get("/assets", summary="The mesh files scenes can use: bundled and uploaded")
async def listing(request: Request) -> dict[str, Any]:
    library = _library(request)
    return {"bundled": library.bundled_names(), "uploaded": library.uploaded_names()}


SERVED: dict[int | str, dict[str, Any]] = {
    **NOT_FOUND, 403: {"model": ErrorBody, "description": "Not a plain file name (forbidden)"},
    200: {"content": {media: {} for media in MEDIA_TYPES.values()}, "description": "The file"}}


@router.get("/assets/{name:path}", responses=SERVED, response_class=FileResponse,
            summary="An uploaded mesh file (viewers load meshes from here)")
async def download(request: Request, name: str) -> FileResponse:
    library = _library(request)
    plain = plain_name(name)  # refuses paths, URLs and encodings before any file is opened
    if library.uploads is None or not (library.uploads / plain).is_file():
        raise UnknownAsset(f"no uploaded mesh file {plain!r}", filename=name)
    return FileResponse(library.uploads / plain, media_type=MEDIA_TYPES[plain.rsplit(".", 1)[1]],
                        headers={"Cache-Control": "public, max-age=31536000, immutable"})

