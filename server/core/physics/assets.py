"""Mesh files that parts are made from: the bundled ones and uploaded ones, by safe names.

A filename is taken as 1.0 pages wrote it (``'../assets/gltf/round-palm.glb'``,
``'round-palm.glb'``, ``'/assets/gltf/round-palm.glb'``): after one of the known
prefixes, what is left must be a plain file name (letters, digits, ``_-.``, ending in
``.glb`` or ``.gltf``) of a bundled or uploaded file. Anything else (other folders, ``..``,
absolute paths, URLs, percent-encoding, backslashes) is refused before any file is opened.

The mesh of a file is read once per process (trimesh). An upload must be a self-contained
glTF (GLB, or JSON with its buffers as ``data:`` URIs) whose mesh trimesh reads, within
the size limits (:func:`checked_mesh`); the server keeps it under the hash of its bytes
(:mod:`server.web.storage.upload_folder`: the core reads files, it writes none).
"""

from __future__ import annotations

import io
import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from ..kit.errors import BadAsset, Forbidden, UnknownAsset
from ..kit.limits import DEFAULT, MAX_SIZE, Limits
from . import gltf_file
from .robot_description import RobotDescription

BUNDLED_DIR = Path(__file__).resolve().parents[3] / "assets" / "gltf"
BUNDLED_URL = "/assets/gltf/"
UPLOADED_URL = "/api/assets/"
PREFIXES = ("../assets/gltf/", "./assets/gltf/", "assets/gltf/", BUNDLED_URL, UPLOADED_URL)
_NAME = re.compile(r"[A-Za-z0-9_-]+(?:\.[A-Za-z0-9_-]+)*\.(?:glb|gltf|robot)")


@dataclass(frozen=True, eq=False)  # compared and hashed by identity: one per file read
class MeshFile:
    """A file's triangles in the file's own frame, ready for rays and envelopes."""

    url: str
    vertices: np.ndarray   # (n, 3) float
    triangles: np.ndarray  # (m, 3) vertex indices, counter-clockwise seen from outside


class Uploads(Protocol):
    """Where uploaded files are kept (the core writes none itself)."""

    def store(self, data: bytes, limits: Limits) -> dict[str, Any]:
        """Keep a checked glTF mesh: its ``name`` (and URL, size, triangles)."""

    def store_robot(self, description: RobotDescription, limits: Limits) -> dict[str, Any]:
        """Keep a robot read from a file: its ``name`` (and URL, size)."""


class AssetLibrary:
    """Finds mesh files by name: bundled ones, then those uploaded to ``uploads``."""

    def __init__(self, bundled: Path = BUNDLED_DIR, uploads: Path | None = None,
                 limits: Limits = DEFAULT) -> None:
        self.bundled = bundled
        self.uploads = uploads
        self.limits = limits  # what a file read for a part may expand to

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

    def uploaded_names(self) -> list[str]:
        """Names of the files uploaded so far."""
        if self.uploads is None:
            return []
        try:
            return sorted(p.name for p in self.uploads.iterdir() if _NAME.fullmatch(p.name))
        except FileNotFoundError:  # a folder that could not be made: nothing was uploaded
            return []

    def bundled_names(self) -> list[str]:
        """Names of the files that come with the server."""
        return sorted(p.name for p in self.bundled.glob("*.gl*"))

    def mesh(self, filename: str) -> MeshFile:
        """The mesh of a file (read once per process)."""
        path, url = self._located(filename, ("glb", "gltf"), "mesh")
        return _read_mesh(str(path), url, path.stat().st_mtime_ns, self.limits)

    def robot(self, filename: str) -> RobotDescription:
        """The robot an uploaded ``.robot`` file describes (read and checked once per process)."""
        path, _ = self._located(filename, ("robot",), "robot")
        return _read_robot(str(path), path.stat().st_mtime_ns)

    def _located(self, filename: str, kinds: tuple[str, ...], what: str) -> tuple[Path, str]:
        path, url = self.locate(filename)
        if path.suffix.lstrip(".") not in kinds:
            raise BadAsset(f"{filename!r} is not a {what} file ({', '.join('.' + k for k in kinds)})")
        return path, url


def placed(geometry: dict[str, Any], vertices: np.ndarray,
           triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A mesh file's vertices and triangles where a mesh part's ``geometry`` puts them:
    mirrored in X (a right-hand part: two corners of each triangle swap back, so faces
    still turn counter-clockwise seen from outside), raised by its offset, stretched by
    its scale."""
    mirror = geometry["mirror"]
    vertices = (np.asarray(vertices, float) * ([-1.0, 1.0, 1.0] if mirror else 1.0)
                + np.asarray(geometry["offset"])) * np.asarray(geometry.get("scale", (1.0, 1.0, 1.0)))
    triangles = np.asarray(triangles)
    return vertices, (triangles[:, [0, 2, 1]] if mirror else triangles)


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


def checked_mesh(data: bytes, limits: Limits) -> tuple[str, np.ndarray, np.ndarray]:
    """The kind (``glb``/``gltf``), triangles and vertices of a self-contained glTF file's
    mesh, judged from its layout before anything is loaded (:mod:`server.core.physics.gltf_file`),
    then read once; or :class:`BadAsset` / :class:`LimitExceeded`."""
    summary = gltf_file.inspect(data, limits)
    faces, vertices = _load(io.BytesIO(data), summary.kind)
    if len(faces) != summary.triangles or (len(faces) and faces.max() >= len(vertices)):
        raise BadAsset("the file's mesh does not read as its layout says")  # a loader quirk
    if not np.isfinite(vertices).all() or np.abs(vertices).max() > MAX_SIZE:
        raise BadAsset(f"the mesh's coordinates must be finite and within ±{MAX_SIZE:g}")
    return summary.kind, faces, vertices


def _load(source: Any, kind: str | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Triangles and vertices of a checked file, its placements applied (materials and
    textures are not read: geometry is all the server needs)."""
    import trimesh  # only scenes that use meshes pay for it

    try:
        mesh = trimesh.load(source, file_type=kind, force="mesh", process=False,
                            skip_materials=True)
        return np.asarray(mesh.faces, dtype=np.int64), np.asarray(mesh.vertices, dtype=float)
    except Exception as error:  # trimesh raises many kinds for broken files
        raise BadAsset(f"the file does not read as a glTF mesh: {str(error)[:200]}") from None


@lru_cache(maxsize=16)
def _read_robot(path: str, version: int) -> RobotDescription:
    return RobotDescription.from_json(Path(path).read_bytes())


@lru_cache(maxsize=64)
def _read_mesh(path: str, url: str, version: int, limits: Limits) -> MeshFile:
    data = Path(path).read_bytes()  # checked again: a file may have been put there by hand
    _, faces, vertices = checked_mesh(data, limits)
    return MeshFile(url, vertices, faces)
