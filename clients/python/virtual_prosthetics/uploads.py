"""Uploading files: ``upload_asset(path)`` gives the name ``GLTFPart`` takes,
``load_robot(path)`` makes the robot a URDF (with its meshes) describes."""

from __future__ import annotations

import io
import json
import zipfile
from pathlib import Path
from typing import Any
from urllib.parse import urlencode

from .http_api import request
from .robots import ImportedRobot
from .session import Session, current_session


def upload_asset(source: str | Path | bytes, scene: Session | None = None) -> str:
    """Upload a GLB (or a glTF with embedded buffers) to the server of ``scene`` (the
    current one by default); the name to give ``GLTFPart``, the same for the same bytes.

    The server refuses files too large, not glTF, pointing at other files, or with too
    many triangles: :class:`ServerError` says which (``too_large``, ``bad_asset``…).
    """
    data = source if isinstance(source, bytes) else Path(source).read_bytes()
    return json.loads(request(scene or current_session(), "/api/assets", "upload", data))["name"]


def load_robot(source: str | Path | bytes, position: Any = None, rotation: Any = None, *,
               file: str | None = None, scene: Session | None = None) -> ImportedRobot:
    """The robot a description makes, in ``scene`` (the current one by default), this
    client's own: ``source`` is a ``.urdf`` file, a zip of a description and its meshes,
    a folder holding them (zipped here), or such bytes. ``position`` ([x, y, z]) and
    ``rotation`` (Euler [x, y, z], radians) place it; ``file`` names the description in a
    zip or folder that holds several. The server reads it (meshes resolve inside the
    upload only); a file it cannot take raises :class:`ServerError` naming what is wrong."""
    session = scene or current_session()
    robot = ImportedRobot(upload_robot(source, file=file, scene=session), scene=session)
    if position is not None:
        robot.set_position(*position)
    if rotation is not None:
        robot.set_rotation(*rotation)
    return robot


def upload_robot(source: str | Path | bytes, *, file: str | None = None,
                 scene: Session | None = None) -> str:
    """Upload a robot description (as :func:`load_robot` takes it) to the server of
    ``scene``; the name ``ImportedRobot`` makes robots of, as many as wanted."""
    query = "" if file is None else "?" + urlencode({"file": file})
    stored = json.loads(request(scene or current_session(), "/api/robots" + query, "load_robot",
                                _bytes(source)))
    return str(stored["file"])


def _bytes(source: str | Path | bytes) -> bytes:
    """A robot upload's body: the bytes, a file's, or a folder's files zipped."""
    if isinstance(source, bytes):
        return source
    path = Path(source)
    if not path.is_dir():
        return path.read_bytes()
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        for member in sorted(p for p in path.rglob("*") if p.is_file()):
            archive.write(member, member.relative_to(path).as_posix())
    return out.getvalue()
