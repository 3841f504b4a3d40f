"""A scene's recordings as its process keeps them: the MCAP file open for writing and the
recorder filling it (:mod:`server.core.recording.mcap_recorder`), one at a time, started by
REST (the server names it) or by a client's ``startRecording`` (named here)."""

from __future__ import annotations

import fcntl
import logging
import time
from pathlib import Path
from typing import IO, Any, Callable, Mapping

from ...core.recording.mcap_recorder import Recorder, RecordingLimits
from ...core.scene.scene import Scene
from ...core.kit.errors import RecordingBusy, StorageFailure, UnknownRecording
from .recordings import new_recording

log = logging.getLogger(__name__)


class RecordingFile:
    """Recording ``id`` of ``scene`` into ``path``: started at once, with a snapshot."""

    def __init__(self, recording_id: str, path: Path, scene: Scene) -> None:
        self.id, self.path, self.scene = recording_id, path, scene
        try:
            self._file: IO[bytes] = open(path, "xb")  # never over another recording
        except FileExistsError:
            raise RecordingBusy(f"a recording {recording_id!r} exists already", recording=recording_id) from None
        except OSError as error:
            raise StorageFailure(f"the recording cannot be written ({error.strerror})") from None
        try:  # held while it records (the kernel lets go when the file closes or this
            # process dies): every server process sharing the folder, a cluster's gateways
            # included, sees it running (server.web.recording.recordings.running)
            fcntl.flock(self._file, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as error:  # a folder whose file system has no locks
            self._file.close()
            path.unlink(missing_ok=True)
            raise StorageFailure(f"the recording's file cannot be locked ({error.strerror})") from None
        limits = scene.limits
        self.recorder = Recorder(self._file, scene, time.time_ns(),
                                 RecordingLimits(limits.recording_bytes, limits.recording_seconds))

    def stop(self, reason: str) -> dict[str, Any]:
        """Finish and close the file; what it holds, and why it stopped."""
        try:
            return {"id": self.id, **self.recorder.finish(reason, self.scene)}
        except Exception:  # a full disk: the file stays as far as it got
            log.exception("recording %s did not finish", self.id)
            return {"id": self.id, "stopped": f"{reason}; its file could not be finished"}
        finally:
            self._file.close()


class SceneRecordings:
    """The scene's recorder (its ``RecordingControl``): at most one recording at a time;
    ``started`` is told a recording's id when a client started one, ``ended`` what a
    recording holds whenever one ends (the server hears of both)."""

    def __init__(self, scene: Scene, folder: Path | None, started: Callable[[str], None],
                 ended: Callable[[dict[str, Any]], None]) -> None:
        self.scene, self.folder = scene, folder
        self._started, self._ended = started, ended
        self.current: RecordingFile | None = None

    def start(self, client: str) -> str:
        """A client's ``startRecording``: a new recording, named here."""
        if self.folder is None:
            raise StorageFailure("this server keeps no recordings")
        recording_id, path = new_recording(self.folder, self.scene.name, self.scene.limits)
        self.begin(recording_id, path)
        self._started(recording_id)
        return recording_id

    def stop(self) -> dict[str, Any]:
        """A client's ``stopRecording``: what the recording holds."""
        if self.current is None:
            raise UnknownRecording(f"scene {self.scene.name!r} is not being recorded")
        return self.end("stopped")

    def begin(self, recording_id: str, path: Path) -> None:
        if self.current is not None:
            raise RecordingBusy(f"scene {self.scene.name!r} is being recorded already "
                                f"({self.current.id}); stop that recording first",
                                recording=self.current.id)
        self.current = RecordingFile(recording_id, path, self.scene)

    def end(self, reason: str) -> dict[str, Any]:
        """Stop the recording there is; what it holds (the server is told too)."""
        recording, self.current = self.current, None
        assert recording is not None
        summary = recording.stop(reason)
        self._ended(summary)
        return summary

    def request(self, client_id: str, text: str | bytes) -> None:
        if self.current is not None:
            self.current.recorder.request(client_id, text, self.scene.time)

    def tick(self, messages: list[Mapping[str, Any]]) -> None:
        """Record a tick's messages; a limit reached ends the recording."""
        if self.current is not None:
            stopped = self.current.recorder.tick(messages, self.scene)
            if stopped:
                self.end(stopped)
