"""Uploading mesh files: ``upload_asset(path)`` gives the name ``GLTFPart`` takes."""

from __future__ import annotations

import json
import urllib.error
import urllib.request
from pathlib import Path

from .errors import ConnectionLost, ServerError
from .session import Session, current_session

UPLOAD_TIMEOUT = 60.0


def upload_asset(source: str | Path | bytes, scene: Session | None = None) -> str:
    """Upload a GLB (or a glTF with embedded buffers) to the server of ``scene`` (the
    current one by default); the name to give ``GLTFPart``, the same for the same bytes.

    The server refuses files too large, not glTF, pointing at other files, or with too
    many triangles: :class:`ServerError` says which (``too_large``, ``bad_asset``…).
    """
    data = source if isinstance(source, bytes) else Path(source).read_bytes()
    scene = scene or current_session()
    base = scene.url
    http = "https" + base[3:] if base.startswith("wss") else "http" + base[2:]
    headers = {"Content-Type": "application/octet-stream",
               **({"Authorization": f"Bearer {scene.token}"} if scene.token else {})}
    request = urllib.request.Request(f"{http}/api/assets", data=data, method="POST",
                                     headers=headers)
    try:
        with urllib.request.urlopen(request, timeout=UPLOAD_TIMEOUT) as answer:
            return json.loads(answer.read())["name"]
    except urllib.error.HTTPError as error:
        body = json.loads(error.read() or b"{}")
        raise ServerError(body.get("code", "http_error"), body.get("message", str(error)),
                          "upload", body.get("details")) from None
    except urllib.error.URLError as error:
        raise ConnectionLost(f"could not upload to {http}: {error.reason}") from None
