"""What ``vp-server --state-dir DIR`` keeps, so that a restart loses nothing::

    DIR/scenes/<scene>.json   each scene as a document (server.core.scene_document),
                              its uploaded files named by content hash, not carried
    DIR/assets/               uploaded mesh files (unless --assets-dir names another folder)
    DIR/server.json           the key resume keys are signed with, and how far client ids
                              have been handed out (ids are never handed out twice)

Every file is written whole under a temporary name, flushed to the disk and renamed over
the old one, then the folder is flushed: after a crash, ``kill -9`` included, each file is
the old one or the new one, never a mix. A scene's file is written by its own process
(:class:`SceneStore`); ``server.json`` by the event loop's (:class:`StateDir`).
"""

from __future__ import annotations

import json
import logging
import os
import secrets
from pathlib import Path
from typing import Any

log = logging.getLogger(__name__)
CLIENT_BLOCK = 1000  # client ids reserved in server.json at a time


def write_atomically(path: Path, data: bytes, mode: int = 0o666) -> None:
    """Replace ``path`` by a file holding ``data``, all at once; ``mode`` (less the umask)
    from the moment the file exists."""
    partial = path.with_name(f".{path.name}.{os.getpid()}.part")
    with open(os.open(partial, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, mode), "wb") as file:
        file.write(data)
        file.flush()
        os.fsync(file.fileno())
    os.replace(partial, path)
    folder = os.open(path.parent, os.O_RDONLY)
    try:
        os.fsync(folder)  # the rename itself survives a power cut
    finally:
        os.close(folder)


class SceneStore:
    """One scene's file (picklable: the scene's process takes it along)."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def load(self) -> Any | None:
        """The saved document (JSON), or None when there is none or it cannot be read
        (then it is set aside, never overwritten: someone may want it back)."""
        try:
            return json.loads(self.path.read_bytes())
        except FileNotFoundError:
            return None
        except (OSError, ValueError) as error:
            self.set_aside(f"it cannot be read ({error})")
            return None

    def asset_names(self) -> set[str]:
        """The uploaded files the saved document names (none when it cannot be read)."""
        try:
            assets = json.loads(self.path.read_bytes()).get("assets", [])
            return {asset["name"] for asset in assets if isinstance(asset.get("name"), str)}
        except (OSError, ValueError, AttributeError, TypeError):
            return set()

    def save(self, data: bytes) -> None:
        """Write the scene's document."""
        write_atomically(self.path, data)

    def set_aside(self, reason: str) -> None:
        """Rename the file ``<name>.json.unreadable-<k>``, telling the log why."""
        for k in range(1, 10_000):
            spare = self.path.with_name(f"{self.path.name}.unreadable-{k}")
            if not spare.exists():
                break
        os.replace(self.path, spare)
        log.error("scene file %s not restored: %s; kept as %s", self.path, reason, spare.name)


class StateDir:
    """The folder: the scenes saved in it, its upload folder, the server's lasting key."""

    def __init__(self, root: Path) -> None:
        self.root = root
        self.scenes = root / "scenes"
        self.assets = root / "assets"
        for folder in (self.root, self.scenes, self.assets):
            folder.mkdir(parents=True, exist_ok=True)
        self._file = root / "server.json"
        saved = self._read()
        self.secret = bytes.fromhex(saved["secret"]) if "secret" in saved else \
            secrets.token_bytes(32)
        self.clients_reserved = int(saved.get("clientsReserved", 0))
        if "secret" not in saved:
            self._write()

    def store(self, scene: str) -> SceneStore:
        """Where the scene ``scene`` is kept (its name is already checked to be a plain one)."""
        return SceneStore(self.scenes / f"{scene}.json")

    def saved_scenes(self) -> list[str]:
        """Names of the scenes that have a file, sorted."""
        return sorted(p.stem for p in self.scenes.glob("*.json"))

    def reserve_clients(self, past: int) -> int:
        """Note that client ids up to ``past`` + a block may have been handed out; the new
        bound. A restarted server starts after it, so no id is handed out twice."""
        self.clients_reserved = past + CLIENT_BLOCK
        self._write()
        return self.clients_reserved

    def _read(self) -> dict[str, Any]:
        try:
            saved = json.loads(self._file.read_bytes())
            return saved if isinstance(saved, dict) else {}
        except FileNotFoundError:
            return {}
        except (OSError, ValueError) as error:
            raise SystemExit(f"{self._file} cannot be read ({error}); move it away to start "
                             f"afresh (resume keys given before then stop working)") from None

    def _write(self) -> None:
        data = {"secret": self.secret.hex(), "clientsReserved": self.clients_reserved}
        # the key signs resume keys: never readable by other users, not even for a moment
        write_atomically(self._file, json.dumps(data).encode(), mode=0o600)
