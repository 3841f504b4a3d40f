"""Uploading mesh files: ``upload_asset(path)`` gives the name ``GLTFPart`` takes."""

from __future__ import annotations

import json
from pathlib import Path

from .http_api import request
from .session import Session, current_session


def upload_asset(source: str | Path | bytes, scene: Session | None = None) -> str:
    """Upload a GLB (or a glTF with embedded buffers) to the server of ``scene`` (the
    current one by default); the name to give ``GLTFPart``, the same for the same bytes.

    The server refuses files too large, not glTF, pointing at other files, or with too
    many triangles: :class:`ServerError` says which (``too_large``, ``bad_asset``…).
    """
    data = source if isinstance(source, bytes) else Path(source).read_bytes()
    return json.loads(request(scene or current_session(), "/api/assets", "upload", data))["name"]
