"""What ``vp-server --state-dir DIR`` keeps, so that a restart loses nothing::

    DIR/scenes/<scene>.json      each scene as a document (server.core.protocol.scene_document),
                                 its uploaded files named by content hash, not carried
    DIR/scenes/<scene>.journal   the changes made since that document was written
                                 (server.web.storage.scene_store)
    DIR/assets/                  uploaded mesh files (unless --assets-dir names another folder)
    DIR/recordings/              recordings of scenes, MCAP files (server.web.recording.recordings)
    DIR/server.json              the key resume keys are signed with, and how far client ids
                                 have been handed out (ids are never handed out twice)

Files are written whole under a temporary name, flushed to the disk and renamed over the
old one, then the folder is flushed: after a crash each file is the old one or the new one.
A scene's files are written by its own process (:class:`SceneStore`); ``server.json`` by
the event loop's (:class:`StateDir`).

A start always succeeds: a folder that cannot be written, a ``server.json`` that cannot be
read (set aside, a new key made) or a file in ``scenes/`` that is no scene's (set aside)
is reported (the log, ``/api/health``), never fatal. Saved scenes are opened when they are
first used, so however many there are, they cost nothing until then.
"""

from __future__ import annotations

import json
import logging
import re
import secrets
from pathlib import Path
from typing import Any

from .scene_store import SceneStore, set_aside, write_atomically

log = logging.getLogger(__name__)
CLIENT_BLOCK = 1000  # client ids reserved in server.json at a time
SCENE_NAME = re.compile(r"[A-Za-z0-9_-]{1,64}")
SCENE_FILES = (".json", ".journal")
_SECRET = re.compile(r"[0-9a-f]{64}")


class StateDir:
    """The folder: the scenes saved in it, its upload folder, the server's lasting key, and
    what is wrong with it (:attr:`problems`)."""

    def __init__(self, root: Path) -> None:
        self.root = root
        self.scenes = root / "scenes"
        self.assets = root / "assets"
        self.problems: dict[str, str] = {}  # what -> what is wrong (health shows them)
        for folder in (self.root, self.scenes, self.assets):
            try:
                folder.mkdir(parents=True, exist_ok=True)
            except OSError as error:
                self._problem("folder", f"{folder} cannot be made ({error.strerror})")
        self._file = root / "server.json"
        saved = self._read()
        self.secret = bytes.fromhex(saved["secret"]) if "secret" in saved else \
            secrets.token_bytes(32)
        self.clients_reserved = saved.get("clientsReserved", 0)
        if "secret" not in saved:
            self._write()
        self.tidy()

    def store(self, scene: str) -> SceneStore:
        """Where the scene ``scene`` is kept (its name is already checked to be a plain one)."""
        return SceneStore(self.scenes / f"{scene}.json")

    def saved_scenes(self) -> list[str]:
        """Names of the scenes that have a file, sorted."""
        try:
            files = list(self.scenes.iterdir())
        except OSError:
            return []
        return sorted({p.stem for p in files
                       if p.suffix in SCENE_FILES and SCENE_NAME.fullmatch(p.stem)})

    def tidy(self) -> None:
        """Set aside the files in ``scenes/`` that no scene can have (a name that is not a
        scene name: ``my lab.json``, ``lab.old.json``), one warning each: left there, they
        would be looked at again at every start."""
        try:
            files = list(self.scenes.iterdir())
        except OSError as error:
            self._problem("scenes", f"{self.scenes} cannot be read ({error.strerror})")
            return
        for path in files:
            if path.suffix in SCENE_FILES and not SCENE_NAME.fullmatch(path.stem) \
                    and not path.name.startswith("."):
                set_aside(path, "is no scene's file (scene names are 1-64 letters, digits, "
                                "_ or -)", suffix="ignored")

    def reserve_clients(self, past: int) -> int:
        """Note that client ids up to ``past`` + a block may have been handed out; the new
        bound. A restarted server starts after it, so no id is handed out twice. When the
        note cannot be written the server goes on (reported): the owners of saved objects
        are reserved again whenever their scene opens, which is what ids protect."""
        self.clients_reserved = past + CLIENT_BLOCK
        self._write()
        return self.clients_reserved

    def _read(self) -> dict[str, Any]:
        try:
            saved = json.loads(self._file.read_bytes())
            if not isinstance(saved, dict) or not isinstance(saved.get("secret"), str) or \
                    not _SECRET.fullmatch(saved["secret"]) or \
                    type(saved.get("clientsReserved", 0)) is not int or \
                    saved.get("clientsReserved", 0) < 0:
                raise ValueError("it is not a key of 64 hex digits and a count of client ids")
            return saved
        except FileNotFoundError:
            return {}
        except (OSError, ValueError, RecursionError) as error:
            set_aside(self._file, f"cannot be read ({str(error)[:120]}): a new key is made; "
                                  f"resume keys given before stop working")
            return {}

    def _write(self) -> None:
        data = {"secret": self.secret.hex(), "clientsReserved": self.clients_reserved}
        try:
            # the key signs resume keys: never readable by other users, not even for a moment
            write_atomically(self._file, json.dumps(data).encode(), mode=0o600)
        except OSError as error:
            self._problem("server.json", f"{self._file} cannot be written ({error.strerror}): "
                                         f"client ids handed out are not noted")
        else:
            self._solved("server.json")

    def _problem(self, key: str, text: str) -> None:
        if self.problems.get(key) != text:
            log.error("state folder: %s", text)
        self.problems[key] = text

    def _solved(self, key: str) -> None:
        if self.problems.pop(key, None) is not None:
            log.info("state folder: %s is written again", key)
