"""The server's upload folder: uploaded mesh and robot files kept under the hash of their
bytes (``<sha256>.glb``, ``.robot``), so the same file uploaded twice is one file with
one name; files no scene uses are collected to make room. Scenes read them through the
core's :class:`~server.core.physics.assets.AssetLibrary`, which writes nothing."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path
from typing import Any, Collection

from ...core.kit.errors import Forbidden, InternalError, LimitExceeded, TooLarge
from ...core.kit.limits import Limits
from ...core.physics.assets import UPLOADED_URL, AssetLibrary, checked_mesh
from ...core.physics.robot_description import RobotDescription


class UploadFolder:
    """Keeps uploads in ``library``'s upload folder (the core's ``Uploads``)."""

    def __init__(self, library: AssetLibrary) -> None:
        self.library = library

    def store(self, data: bytes, limits: Limits) -> dict[str, Any]:
        """Keep an uploaded glTF file; its name, URL, size and triangle count."""
        self._folder()  # (refused before the file is read)
        if len(data) > limits.asset_bytes:
            raise TooLarge(f"the file has {len(data)} bytes; at most {limits.asset_bytes} "
                           f"are taken", limit="assetBytes", value=limits.asset_bytes)
        kind, faces, _ = checked_mesh(data, limits)
        return {**self._keep(data, kind, limits), "triangles": len(faces)}

    def store_robot(self, description: RobotDescription, limits: Limits) -> dict[str, Any]:
        """Keep a robot read from a file (its links' meshes kept already); its name, URL
        and size."""
        return self._keep(description.to_json(), "robot", limits)

    def _keep(self, data: bytes, kind: str, limits: Limits) -> dict[str, Any]:
        """Keep checked bytes under their hash, once."""
        name = f"{hashlib.sha256(data).hexdigest()[:32]}.{kind}"
        path = self._folder() / name
        if path.is_file():
            os.utime(path)  # uploaded again: as new (see collect)
        else:
            if len(self.library.uploaded_names()) >= limits.assets:
                raise LimitExceeded(f"the server keeps at most {limits.assets} uploaded files",
                                    limit="assets", value=limits.assets)
            partial = path.with_name(f".{name}.{os.getpid()}.part")
            try:
                partial.write_bytes(data)
                os.replace(partial, path)  # never a half-written file under the name
            except OSError as error:
                partial.unlink(missing_ok=True)
                raise InternalError(f"the upload folder cannot be written ({error.strerror}); "
                                    f"nothing was kept") from None
        return {"name": name, "url": UPLOADED_URL + name, "bytes": len(data)}

    def _folder(self) -> Path:
        """The folder uploads are kept in; :class:`Forbidden` when the server has none."""
        if self.library.uploads is None:
            raise Forbidden("this server takes no uploads")
        return self.library.uploads

    def collect(self, in_use: Collection[str], before: float) -> list[str]:
        """Remove the uploaded files not ``in_use`` last uploaded before ``before`` (a
        ``time.time()``), to make room for new ones; their names. Recent ones stay: a
        script may have uploaded a file it has not used yet."""
        removed = []
        for name in self.library.uploaded_names():
            path = self.library.uploads / name  # type: ignore[operator]
            try:
                if name not in in_use and path.stat().st_mtime < before:
                    path.unlink()
                    removed.append(name)
            except FileNotFoundError:
                pass
        return removed
