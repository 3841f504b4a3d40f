"""One scene's files in the state folder: its document and the journal of changes since.

``NAME.json`` is the scene as a document (:mod:`server.core.protocol.scene_document`), written whole
now and then. ``NAME.journal`` holds every change clients made since that document was
written, one line each (:mod:`server.core.protocol.command_log`), appended before the change is
acknowledged: a change answered ``ok`` is in the kernel's hands before the answer leaves,
so killing any of the server's processes (``kill -9`` included) loses none. Power cuts are
another matter: the journal is flushed to the disk at most a second after a change
(:meth:`SceneStore.flush`), documents as they are written.

The journal's first line names the document it follows by the hash of its bytes. Writing
a document starts a new journal after it; a crash between the two leaves a journal that
names the older document, and such a journal is left out (its changes are in the newer
document already).
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
from pathlib import Path
from typing import Any

log = logging.getLogger(__name__)
JOURNAL_FORMAT = "virtual-prosthetics-journal"


def write_atomically(path: Path, data: bytes, mode: int = 0o666) -> None:
    """Replace ``path`` by a file holding ``data``, all at once; ``mode`` (less the umask)
    from the moment the file exists."""
    partial = path.with_name(f".{path.name}.{os.getpid()}.part")
    try:
        with open(os.open(partial, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, mode), "wb") as file:
            file.write(data)
            file.flush()
            os.fsync(file.fileno())
        os.replace(partial, path)
    except BaseException:
        partial.unlink(missing_ok=True)  # a full disk leaves no partial file behind
        raise
    folder = os.open(path.parent, os.O_RDONLY)
    try:
        os.fsync(folder)  # the rename itself survives a power cut
    finally:
        os.close(folder)


def set_aside(path: Path, reason: str, suffix: str = "unreadable") -> Path | None:
    """Rename ``path`` to ``<name>.<suffix>-<k>`` (never overwriting), telling the log why;
    the new path (None when even that failed: the log says so)."""
    for k in range(1, 10_000):
        spare = path.with_name(f"{path.name}.{suffix}-{k}")
        if not spare.exists():
            break
    try:
        os.replace(path, spare)
    except OSError as error:
        log.error("%s %s; it could not be set aside either (%s)", path, reason, error)
        return None
    log.error("%s %s; kept as %s", path, reason, spare.name)
    return spare


def _digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


class SceneStore:
    """One scene's document and journal (picklable: the scene's process takes it along and
    opens the journal there)."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.journal_path = path.with_suffix(".journal")
        self._document: str | None = None  # the hash of the document the journal follows
        self._journal: int | None = None   # the journal's descriptor, opened to append
        self._unflushed = False
        self.journal_bytes = 0

    def __getstate__(self) -> dict[str, Any]:
        return {"path": self.path}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__init__(state["path"])  # type: ignore[misc]

    def load(self) -> Any | None:
        """The saved document (JSON), or None when there is none or it cannot be read
        (then it and its journal are set aside, never overwritten: someone may want them)."""
        try:
            data = self.path.read_bytes()
            document = json.loads(data)
        except FileNotFoundError:
            return None
        except (OSError, ValueError, RecursionError) as error:
            self.set_aside(f"it cannot be read ({str(error)[:200]})")
            return None
        self._document = _digest(data)
        return document

    def journal(self) -> list[bytes]:
        """The lines of the journal that follows the loaded document (none for a journal
        that follows another one: its changes are in the document already)."""
        try:
            lines = self.journal_path.read_bytes().split(b"\n")
        except FileNotFoundError:
            return []
        except OSError as error:
            log.error("journal %s cannot be read (%s); changes since its document are "
                      "lost", self.journal_path, error)
            return []
        try:
            header = json.loads(lines[0])
            follows = header["after"] if header.get("format") == JOURNAL_FORMAT else ""
        except (ValueError, TypeError, KeyError, AttributeError):
            follows = ""
        if follows != self._document:
            return []  # written before the document: nothing in it is news
        return [line for line in lines[1:] if line]

    def append(self, lines: bytes) -> None:
        """Add lines to the journal (started after the current document if it has none);
        on the disk when this returns, but for a power cut (:meth:`flush`)."""
        if self._journal is None:
            self._journal = self._open_journal()
        written = os.write(self._journal, lines)
        while written < len(lines):  # a write may take part of it (a signal, a full pipe)
            written += os.write(self._journal, lines[written:])
        self.journal_bytes += len(lines)
        self._unflushed = True

    def _open_journal(self) -> int:
        if not self._journal_follows():
            self._start_journal()  # none yet, or one that an older document had
        return os.open(self.journal_path, os.O_WRONLY | os.O_APPEND)

    def _journal_follows(self) -> bool:
        try:
            with open(self.journal_path, "rb") as file:
                header = json.loads(file.readline())
            return header.get("after") == self._document
        except (OSError, ValueError, AttributeError, RecursionError):
            return False

    def _start_journal(self) -> None:
        header = {"format": JOURNAL_FORMAT, "after": self._document}
        write_atomically(self.journal_path, json.dumps(header).encode() + b"\n")
        self.journal_bytes = 0

    def flush(self) -> None:
        """Put what was appended on the disk itself (a power cut spares it)."""
        if self._journal is not None and self._unflushed:
            os.fdatasync(self._journal)
            self._unflushed = False

    def save(self, data: bytes) -> None:
        """Write the scene's document; the journal starts again after it."""
        write_atomically(self.path, data)
        self._document = _digest(data)
        self.close()
        self._start_journal()  # a crash before this: the old journal is left out at start

    @property
    def journaled(self) -> bool:
        """Whether changes are being written to a journal that follows the document."""
        return self._journal is not None

    def forget_journal(self) -> None:
        """The scene was replaced whole and its document could not be written: the journal
        (and any journal started from now on) must never be replayed on the old document."""
        self.close()
        self._document = "replaced, unsaved"

    def close(self) -> None:
        """Close the journal (it is opened again by the next :meth:`append`)."""
        if self._journal is not None:
            os.close(self._journal)
            self._journal = None

    def asset_names(self) -> set[str]:
        """The uploaded files the saved document names (none when it cannot be read)."""
        try:
            assets = json.loads(self.path.read_bytes()).get("assets", [])
            return {asset["name"] for asset in assets if isinstance(asset.get("name"), str)}
        except (OSError, ValueError, AttributeError, TypeError, RecursionError):
            return set()

    def set_aside(self, reason: str) -> None:
        """Set the document (and its journal) aside: ``<name>.json.unreadable-<k>``."""
        set_aside(self.path, f"not restored: {reason}")
        if self.journal_path.exists():
            set_aside(self.journal_path, "follows a document that was set aside")
        self._document = None
