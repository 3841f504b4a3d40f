"""``GET /api/scenes/{scene}/picture``: the scene as its camera sees it, drawn in the
scene's process by PyBullet's software renderer (:mod:`server.core.physics.picture_world`),
as a PNG (``format=png``, for people) or raw RGB rows (``format=rgb``, for programs: a
learning environment's ``rgb_array``; ``X-Width`` and ``X-Height`` say its size)."""

from __future__ import annotations

import io
import weakref
from typing import Any, Literal

import numpy as np
import pybullet
from fastapi import APIRouter, Request, Response

from ...core.scene.scene import Scene
from ..process.messages import Read
from .rest_base import NOT_FOUND, ErrorBody, hub_of

router = APIRouter(prefix="/api")
PICTURE: dict[int | str, dict[str, Any]] = {
    **NOT_FOUND, 200: {"content": {"image/png": {}, "application/octet-stream": {}},
                       "description": "The picture"},
    400: {"model": ErrorBody, "description": "A side outside 16-1024 pixels (out_of_range)"}}


@router.get("/scenes/{scene}/picture", responses=PICTURE, response_class=Response,
            summary="The scene from its camera, drawn by PyBullet's software renderer: PNG or raw RGB")
async def scene_picture(request: Request, scene: str, width: int = 320, height: int = 240,
                        format: Literal["png", "rgb"] = "png") -> Response:
    body = await hub_of(request, scene).runner.call(Read(_drawn, (width, height, format)))
    media = "image/png" if format == "png" else "application/octet-stream"
    return Response(body, media_type=media, headers={"X-Width": str(width), "X-Height": str(height)})


_WORLDS: weakref.WeakKeyDictionary[Scene, Any] = weakref.WeakKeyDictionary()  # PictureWorld


def _drawn(scene: Scene, width: int, height: int, format: str) -> bytes:
    """The picture's bytes (in the scene's process: travels there by name)."""
    # here, not at the top: the web process never draws, and scipy is half a second of its
    # start (Pillow a sixth of one)
    from PIL import Image

    from ...core.physics.picture_world import PictureWorld
    scene.bodies.sync()  # what changed since the last tick, as every reader sees it
    if scene not in _WORLDS:
        _WORLDS[scene] = PictureWorld(pybullet)
        weakref.finalize(scene, _WORLDS[scene].close)
    pixels = _WORLDS[scene].draw(scene.bodies.physics, scene.camera.position, scene.camera.target,
                                 width, height)
    if format == "rgb":
        return np.ascontiguousarray(pixels).tobytes()
    encoded = io.BytesIO()
    Image.fromarray(pixels).save(encoded, format="PNG")
    return encoded.getvalue()
