"""Recordings of a session's scene (not in the manual): ``rec = vp.start_recording()``,
``rec.stop()``, ``rec.save("trial.mcap")``. The server writes them (MCAP: Foxglove opens
them, the ``mcap`` package reads them). Starting is the scene call ``startRecording``;
stopping one by its id and fetching its file go over REST, with the session's token."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from . import http_api
from .session import SCENE_ID, Session, current_session


class Recording:
    """A recording the server is making (or made) of a session's scene."""

    def __init__(self, session: Session, recording_id: str) -> None:
        self.session, self.id = session, recording_id
        self.summary: dict[str, Any] | None = None  # what it holds, once stopped

    def stop(self) -> dict[str, Any]:
        """Stop it (this client's earlier changes in it first); what it holds: ``bytes``,
        ``seconds``, ``ticks``, ``requests``, ``readings``, and why it ``stopped``."""
        self.session.sync()
        answer = http_api.request(self.session, f"/api/recordings/{self.id}/stop", "stop_recording", b"")
        self.summary = json.loads(answer)
        return self.summary

    def save(self, path: str | Path) -> Path:
        """Write the recording's MCAP file to ``path`` (stopping it first if it runs)."""
        if self.summary is None:
            self.stop()
        target = Path(path)
        target.write_bytes(http_api.request(self.session, f"/api/recordings/{self.id}", "save_recording"))
        return target


def start_recording(scene: Session | None = None) -> Recording:
    """Manual-style ``startRecording()``: record the scene of ``scene`` (the current session
    by default), every frame, request and watched reading from now (after this client's
    earlier requests), with their times, until :meth:`Recording.stop`."""
    session = scene or current_session()
    return Recording(session, session.call(SCENE_ID, "startRecording", wait=True))


def stop_recording(scene: Session | None = None) -> dict[str, Any]:
    """``stopRecording()``: stop the recording of the scene, whoever started it; what it
    holds (as :meth:`Recording.stop` answers)."""
    return (scene or current_session()).call(SCENE_ID, "stopRecording", wait=True)
