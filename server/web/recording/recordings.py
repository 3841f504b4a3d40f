"""The server's recordings: MCAP files in one folder (``--state-dir``'s ``recordings/``, or
a temporary folder that goes with the server), and which scene is filling which.

A recording's id names its file: ``<scene>-<UTC time>-<4 hex digits>.mcap``. Scene
processes write the files (:mod:`server.web.recording.recording_file`); this side hands out ids,
lists the files with what each holds (read from its MCAP summary, once per version of the
file) and hands finished ones out. A file is being recorded while its writer holds its
lock (:func:`running`), whichever process of a cluster started it.
"""

from __future__ import annotations

import fcntl
import re
import secrets
import tempfile
import time
from pathlib import Path
from typing import Any

from mcap.reader import make_reader

from ...core.kit.limits import Limits
from ...core.kit.errors import LimitExceeded, RecordingBusy, RecordingDamaged, UnknownRecording

RECORDING_ID = re.compile(r"[A-Za-z0-9_-]{1,64}-\d{8}T\d{6}Z-[0-9a-f]{4}")
SUFFIX = ".mcap"


class Recordings:
    """Recordings in ``folder`` (None: a temporary one, removed when the server stops)."""

    def __init__(self, folder: Path | None = None, limits: Limits | None = None) -> None:
        self.limits = limits or Limits()
        self._temporary = tempfile.TemporaryDirectory(prefix="vp-recordings-") if folder is None else None
        self.folder = Path(self._temporary.name) if self._temporary is not None else folder
        try:
            self.folder.mkdir(parents=True, exist_ok=True)  # type: ignore[union-attr]
        except OSError:  # the state folder's problem, reported there; recording says it too
            pass
        self.active: dict[str, str] = {}  # recording id -> scene filling it (started here)
        self._read: dict[str, tuple[tuple[int, int], dict[str, Any]]] = {}  # id -> (version, summary)

    def close(self) -> None:
        """The temporary folder goes (a state folder's stay)."""
        if self._temporary is not None:
            self._temporary.cleanup()

    def new(self, scene: str) -> tuple[str, Path]:
        """A new recording's id and the path of its file (the oldest go to make room)."""
        return new_recording(self.folder, scene, self.limits)  # type: ignore[arg-type]

    def started(self, recording_id: str, scene: str) -> None:
        self.active[recording_id] = scene

    def ended(self, recording_id: str) -> None:
        """It stopped (asked to, at a limit, or with its scene)."""
        self.active.pop(recording_id, None)

    def scene_ended(self, scene: str) -> None:
        """Its scene's process is gone: what it was recording is as far as it got."""
        for recording_id in [r for r, s in self.active.items() if s == scene]:
            self.ended(recording_id)

    def path(self, recording_id: str) -> Path:
        """The file of a recording (``unknown_recording`` for an id the server has not; a
        symbolic link is none: the server reads only files its scenes wrote there)."""
        path = self.folder / f"{recording_id}{SUFFIX}"  # type: ignore[operator]
        if not RECORDING_ID.fullmatch(recording_id) or path.is_symlink() or not path.is_file():
            raise UnknownRecording(f"no recording {recording_id[:80]!r}", recording=recording_id[:80])
        return path

    def recording(self, recording_id: str, path: Path | None = None) -> str | None:
        """The scene recording it now (None: it has stopped), whoever started it (``path``:
        its file, when known already)."""
        if running(path or self.path(recording_id)):
            return self.active.get(recording_id, scene_of(recording_id))
        self.active.pop(recording_id, None)  # (its scene ended unheard of: it ended too)
        return None

    def finished(self, recording_id: str) -> Path:
        """The file of a recording that has stopped (``recording_busy`` while it runs)."""
        path = self.path(recording_id)
        if self.recording(recording_id, path) is not None:
            raise RecordingBusy(f"recording {recording_id} is still running; stop it first "
                                f"(POST /api/recordings/{recording_id}/stop)", recording=recording_id)
        return path

    def readable(self, recording_id: str) -> Path:
        """The file of a finished recording that reads as one (``recording_damaged``,
        naming why, for a file cut short or changed: a replay or resimulation of it would
        fail part-way)."""
        path = self.finished(recording_id)
        damage = self.describe(recording_id).get("damage")
        if damage is not None:
            raise RecordingDamaged(f"recording {recording_id} cannot be read: {damage}",
                                   recording=recording_id)
        return path

    def listing(self) -> list[dict[str, Any]]:
        """Every recording, newest first: id, scene, state, bytes, and for a finished one
        its start, duration and message counts."""
        found = []
        for path in sorted(self.folder.glob(f"*{SUFFIX}"), reverse=True):  # type: ignore[union-attr]
            recording_id = path.name[:-len(SUFFIX)]
            if RECORDING_ID.fullmatch(recording_id) and not path.is_symlink():
                found.append(self.describe(recording_id))
        return found

    def describe(self, recording_id: str) -> dict[str, Any]:
        """What one recording holds."""
        path = self.path(recording_id)
        stat = path.stat()
        entry = {"id": recording_id, "scene": scene_of(recording_id), "bytes": stat.st_size}
        if self.recording(recording_id, path) is not None:
            return {**entry, "state": "recording"}
        version = (stat.st_size, stat.st_mtime_ns)
        cached = self._read.get(recording_id)
        if cached is None or cached[0] != version:
            cached = self._read[recording_id] = (version, _summary(path))
        return {**entry, **cached[1]}


def scene_of(recording_id: str) -> str:
    """The scene a recording is of (its id names it)."""
    return recording_id.rsplit("-", 2)[0]


def running(path: Path) -> bool:
    """Whether a scene's process is still writing the recording ``path`` (it holds the
    file's lock: :class:`server.web.recording.recording_file.RecordingFile`)."""
    try:
        with open(path, "rb") as stream:
            fcntl.flock(stream, fcntl.LOCK_SH | fcntl.LOCK_NB)  # let go as it closes
    except BlockingIOError:
        return True
    except OSError:  # gone meanwhile
        return False
    return False


def new_recording(folder: Path, scene: str, limits: Limits) -> tuple[str, Path]:
    """A new recording's id (``<scene>-<UTC time>-<4 hex digits>``) and its file in
    ``folder``, once :func:`make_room` made room for it."""
    make_room(folder, limits)
    stamp = time.strftime("%Y%m%dT%H%M%SZ", time.gmtime())
    recording_id = f"{scene}-{stamp}-{secrets.token_hex(2)}"
    return recording_id, folder / f"{recording_id}{SUFFIX}"


def make_room(folder: Path, limits: Limits) -> None:
    """Remove the oldest finished recordings until fewer than ``recordings`` are kept and
    their bytes are under ``recordingsBytes``; ``limit_exceeded`` if the ones still being
    recorded alone are that many (150 recordings started and stopped kept 153 files)."""
    kept = sorted((p for p in folder.glob(f"*{SUFFIX}")
                   if RECORDING_ID.fullmatch(p.name[:-len(SUFFIX)]) and not p.is_symlink()),
                  key=_age)
    sizes = {path: _size(path) for path in kept}
    count, total = len(kept), sum(sizes.values())
    for path in kept:
        if count < limits.recordings and total < limits.recordings_bytes:
            return
        if not running(path):
            path.unlink(missing_ok=True)
            count, total = count - 1, total - sizes[path]
    if count >= limits.recordings:
        raise LimitExceeded(f"{count} recordings are still being recorded; stop one first",
                            limit="recordings", value=limits.recordings)
    if total >= limits.recordings_bytes:
        raise LimitExceeded(f"the recordings still being recorded hold {total} bytes; stop "
                            f"one first", limit="recordingsBytes", value=limits.recordings_bytes)


def _age(path: Path) -> float:
    try:
        return path.stat().st_mtime
    except OSError:
        return 0.0


def _size(path: Path) -> int:
    try:
        return path.stat().st_size
    except OSError:
        return 0


def _summary(path: Path) -> dict[str, Any]:
    """What a finished file's MCAP summary says (a file cut short: ``damaged``, with the
    ``damage`` the reader found)."""
    try:
        with open(path, "rb") as stream:
            reader = make_reader(stream)
            summary = reader.get_summary()
            metadata = {m.name: m.metadata for m in reader.iter_metadata()}
    except Exception as error:  # the mcap reader raises many kinds for a file without its end
        return {"state": "damaged", "damage": (str(error) or type(error).__name__)[:200]}
    statistics = summary.statistics if summary is not None else None
    if statistics is None:
        return {"state": "damaged", "damage": "it has no MCAP summary: it was cut short"}
    channels = {c.id: c.topic for c in summary.channels.values()}  # type: ignore[union-attr]
    counts = {channels[k]: v for k, v in statistics.channel_message_counts.items()}
    return {"state": "stopped", "stopped": metadata.get("stopped", {}).get("reason"),
            "startedNs": statistics.message_start_time,
            "seconds": (statistics.message_end_time - statistics.message_start_time) / 1e9,
            "messages": counts}
