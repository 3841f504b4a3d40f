"""A scene's recording as its process keeps it: the MCAP file open for writing and the
recorder filling it (:mod:`server.core.recording.mcap_recorder`)."""

from __future__ import annotations

import logging
import time
from pathlib import Path
from typing import IO, Any, Mapping

from ..core.kit.limits import Limits
from ..core.recording.mcap_recorder import Recorder, RecordingLimits
from ..core.scene.scene import Scene
from ..errors import RecordingBusy, StorageFailure

log = logging.getLogger(__name__)


class RecordingFile:
    """Recording ``id`` of ``scene`` into ``path``: started at once, with a snapshot."""

    def __init__(self, recording_id: str, path: Path, scene: Scene, limits: Limits) -> None:
        self.id, self.path = recording_id, path
        try:
            self._file: IO[bytes] = open(path, "xb")  # never over another recording
        except FileExistsError:
            raise RecordingBusy(f"a recording {recording_id!r} exists already", recording=recording_id) from None
        except OSError as error:
            raise StorageFailure(f"the recording cannot be written ({error.strerror})") from None
        self.recorder = Recorder(self._file, scene, time.time_ns(),
                                 RecordingLimits(limits.recording_bytes, limits.recording_seconds))
        self.scene = scene

    def stop(self, reason: str) -> dict[str, Any]:
        """Finish and close the file; what it holds, and why it stopped."""
        try:
            return {"id": self.id, **self.recorder.finish(reason, self.scene)}
        except Exception:  # a full disk: the file stays as far as it got
            log.exception("recording %s did not finish", self.id)
            return {"id": self.id, "stopped": f"{reason}; its file could not be finished"}
        finally:
            self._file.close()

    def tick(self, messages: list[Mapping[str, Any]], scene: Scene) -> str | None:
        """Record a tick's messages; the reason it stopped when a limit stopped it."""
        return self.recorder.tick(messages, scene)
