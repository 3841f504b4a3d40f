"""Mesh files that parts are made from: the bundled ones and uploaded ones, by safe names.

A filename is taken as 1.0 pages wrote it (``'../assets/gltf/round-palm.glb'``,
``'round-palm.glb'``, ``'/assets/gltf/round-palm.glb'``): after one of the known
prefixes, what is left must be a plain file name (letters, digits, ``_-.``, ending in
``.glb`` or ``.gltf``) of a bundled or uploaded file. Anything else (other folders, ``..``,
absolute paths, URLs, percent-encoding, backslashes) is refused before any file is opened.

The mesh of a file is read once per process (trimesh).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import Forbidden, UnknownAsset

BUNDLED_DIR = Path(__file__).resolve().parents[2] / "assets" / "gltf"
BUNDLED_URL = "/assets/gltf/"
UPLOADED_URL = "/api/assets/"
PREFIXES = ("../assets/gltf/", "./assets/gltf/", "assets/gltf/", BUNDLED_URL, UPLOADED_URL)
_NAME = re.compile(r"[A-Za-z0-9_-]+(?:\.[A-Za-z0-9_-]+)*\.(?:glb|gltf)")


@dataclass(frozen=True, eq=False)  # compared and hashed by identity: one per file read
class Mesh:
    """A file's triangles in the file's own frame, ready for rays and envelopes."""

    url: str
    vertices: np.ndarray   # (n, 3) float
    triangles: np.ndarray  # (m, 3) vertex indices, counter-clockwise seen from outside


class AssetLibrary:
    """Finds mesh files by name: bundled ones, then those uploaded to ``uploads``."""

    def __init__(self, bundled: Path = BUNDLED_DIR, uploads: Path | None = None) -> None:
        self.bundled = bundled
        self.uploads = uploads

    def locate(self, filename: str) -> tuple[Path, str]:
        """The file a part's filename means and the URL viewers load it from."""
        name = plain_name(filename)
        path = self.bundled / name
        if path.is_file():
            return path, BUNDLED_URL + name
        if self.uploads is not None and (self.uploads / name).is_file():
            return self.uploads / name, UPLOADED_URL + name
        raise UnknownAsset(f"no mesh file {name!r}: bundled files are "
                           f"{', '.join(self.bundled_names())}; others must be uploaded "
                           f"first (POST /api/assets)", filename=filename)

    def bundled_names(self) -> list[str]:
        """Names of the files that come with the server."""
        return sorted(p.name for p in self.bundled.glob("*.gl*"))

    def mesh(self, filename: str) -> Mesh:
        """The mesh of a file (read once per process)."""
        path, url = self.locate(filename)
        return _read_mesh(str(path), url, path.stat().st_mtime_ns)


def plain_name(filename: str) -> str:
    """The bare file name in ``filename``, or :class:`Forbidden` when it points elsewhere."""
    name = filename
    for prefix in PREFIXES:
        if name.startswith(prefix):
            name = name[len(prefix):]
            break
    if not _NAME.fullmatch(name):
        raise Forbidden(f"mesh filename {filename!r} is not allowed: give a bundled or "
                        f"uploaded file's name, e.g. 'round-palm.glb' or "
                        f"'../assets/gltf/round-palm.glb'", filename=filename)
    return name


@lru_cache(maxsize=64)
def _read_mesh(path: str, url: str, version: int) -> Mesh:
    import trimesh  # only scenes that use meshes pay for it

    loaded = trimesh.load(path, force="mesh", process=False)
    return Mesh(url, np.asarray(loaded.vertices, dtype=float),
                np.asarray(loaded.faces, dtype=np.int64))
