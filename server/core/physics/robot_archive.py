"""The files of an uploaded robot: a zip of a description and its meshes, or one bare file.

Nothing outside the upload is ever opened: member names are checked (no absolute paths,
no ``..``, no backslashes) before anything is read, their sizes are checked against the
limits before they are inflated, and a reference a description makes to a mesh
(``package://NAME/…``, a path relative to the description, ``file://``) resolves among
the members or is refused. Which member is the description: ``file`` when given, else
the one ``.urdf``, else the one MJCF ``.xml`` that no other includes.
"""

from __future__ import annotations

import io
import posixpath
import re
import zipfile
from dataclasses import dataclass

from ..kit.errors import BadAsset, Forbidden, LimitExceeded, TooLarge
from ..kit.limits import Limits

ZIP_MAGIC = b"PK\x03\x04"
_INCLUDE = re.compile(rb"<include\s+file\s*=\s*[\"']([^\"']+)[\"']")


@dataclass(frozen=True)
class RobotArchive:
    """An upload's files by path (``/``-separated, relative to the upload's root), and the
    path of its description."""

    files: dict[str, bytes]
    description: str

    @property
    def folder(self) -> str:
        """The folder of the description: relative references start there."""
        return posixpath.dirname(self.description)

    @property
    def format(self) -> str:
        """``urdf`` or ``mjcf``, from the description's root element."""
        return _format(self.files[self.description]) or "unknown"

    def resolve(self, reference: str) -> tuple[str, bytes]:
        """The member a mesh reference of the description means, and its bytes."""
        if reference.startswith("package://"):
            return self._package(reference[len("package://"):], reference)
        if reference.startswith("file://"):
            reference = reference[len("file://"):]
        if re.match(r"[a-z][a-z0-9+.-]*://", reference) or reference.startswith("/"):
            raise Forbidden(f"mesh {reference!r}: only paths inside the upload are read "
                            f"(relative to the description, or package://NAME/…)", filename=reference)
        path = inside_upload(posixpath.join(self.folder, reference), reference)
        if path not in self.files:
            raise BadAsset(f"mesh {reference!r} is not in the upload (looked for {path!r})")
        return path, self.files[path]

    def _package(self, rest: str, reference: str) -> tuple[str, bytes]:
        """``package://NAME/PATH``: a folder NAME anywhere in the upload holding PATH, else
        PATH from the upload's root or from the description's folder and those above it."""
        name, _, inner = rest.partition("/")
        inner = inside_upload(inner, reference)
        suffix = f"{name}/{inner}"
        found = sorted(p for p in self.files if p == suffix or p.endswith("/" + suffix))
        if found:
            return found[0], self.files[found[0]]
        folder = self.folder
        while True:
            path = posixpath.join(folder, inner) if folder else inner
            if path in self.files:
                return path, self.files[path]
            if not folder:
                break
            folder = posixpath.dirname(folder)
        raise BadAsset(f"mesh {reference!r} is not in the upload (no {suffix!r} or {inner!r})")


def open_archive(data: bytes, file: str | None, limits: Limits) -> RobotArchive:
    """The files of an upload (a zip, or a bare ``.urdf``/MJCF ``.xml``), checked."""
    if not data.startswith(ZIP_MAGIC):
        if file is not None:
            raise BadAsset(f"?file={file} names a file inside a zip; the body is one bare file")
        kind = _format(data)
        if kind is None:
            raise BadAsset("the body is neither a zip nor a URDF (<robot>) or MJCF (<mujoco>) file")
        name = "robot.urdf" if kind == "urdf" else "robot.xml"
        return RobotArchive({name: data}, name)
    files = _members(data, limits)
    return RobotArchive(files, _description(files, file))


def _members(data: bytes, limits: Limits) -> dict[str, bytes]:
    try:
        archive = zipfile.ZipFile(io.BytesIO(data))
        entries = [e for e in archive.infolist() if not e.is_dir()]
    except (zipfile.BadZipFile, ValueError, EOFError) as error:
        raise BadAsset(f"the body is not a readable zip: {str(error)[:120]}") from None
    if len(entries) > limits.robot_files:
        raise LimitExceeded(f"the zip holds {len(entries)} files; at most {limits.robot_files} "
                            f"are taken", limit="robotFiles", value=limits.robot_files)
    total = sum(e.file_size for e in entries)
    if total > limits.robot_bytes:
        raise TooLarge(f"the zip's files come to {total} bytes; at most {limits.robot_bytes} are "
                       f"taken", limit="robotBytes", value=limits.robot_bytes)
    files = {}
    for entry in entries:
        path = inside_upload(entry.filename, entry.filename)
        try:
            content = archive.read(entry)
        except Exception as error:  # zipfile raises many kinds for damaged members
            raise BadAsset(f"{path} in the zip cannot be read: {str(error)[:120]}") from None
        if len(content) != entry.file_size:  # a member that inflates past what it declared
            raise BadAsset(f"{path} in the zip is not the size its entry says")
        files[path] = content
    return files


def inside_upload(path: str, reference: str) -> str:
    """``path`` normalised, or :class:`Forbidden` if it leaves the upload."""
    if "\\" in path or path.startswith("/") or "\0" in path:
        raise Forbidden(f"path {reference!r} is not allowed: only plain relative paths inside "
                        f"the upload", filename=reference)
    normal = posixpath.normpath(path)
    if normal == ".." or normal.startswith("../") or normal in ("", "."):
        raise Forbidden(f"path {reference!r} leaves the upload; only files inside it are read",
                        filename=reference)
    return normal


def _format(data: bytes) -> str | None:
    """``urdf`` or ``mjcf`` by the first element of an XML file (None: neither)."""
    head = re.sub(rb"<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^\[>]*(?:\[.*?\])?\s*>|\s", b"", data[:4096],
                  flags=re.S)
    if head.startswith(b"<robot"):
        return "urdf"
    if head.startswith(b"<mujoco"):
        return "mjcf"
    return None


def _description(files: dict[str, bytes], file: str | None) -> str:
    if file is not None:
        path = inside_upload(file, file)
        if path not in files:
            raise BadAsset(f"?file={file}: the zip has no such file")
        return path
    urdfs = sorted(p for p in files if p.lower().endswith(".urdf"))
    if len(urdfs) == 1:
        return urdfs[0]
    models = sorted(p for p in files if p.lower().endswith(".xml") and _format(files[p]) == "mjcf")
    included = {posixpath.basename(m.decode(errors="replace"))
                for p in models for m in _INCLUDE.findall(files[p])}
    mains = [p for p in models if posixpath.basename(p) not in included]
    candidates = urdfs or mains
    if len(candidates) == 1:
        return candidates[0]
    if not candidates:
        raise BadAsset("the zip holds no .urdf file and no MJCF .xml file")
    raise BadAsset(f"the zip holds several robot descriptions ({', '.join(candidates[:6])}): "
                   f"name one with ?file=PATH")
