"""REST routes of recordings: start one of a scene, stop it, list them, download one.

A scene's process writes its recording (:mod:`server.web.recording.recording_file`); these routes
ask it to start and stop, and serve the finished files (:mod:`server.web.recording.recordings`).
"""

from __future__ import annotations

import math
from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import FileResponse

from ...core.recording import replay
from ...core.recording.resimulate import resimulate_file
from ...core.kit.errors import OutOfRange
from .access import changing_allowed
from ..process.messages import Record, Unrecord
from ..scenes.offload import hang_up_of
from .rest_base import NOT_FOUND, ErrorBody, hub_of, hubs_of

router = APIRouter(prefix="/api")
WINDOW_SECONDS = 10.0  # of ticks one request may ask for (a player asks for the next second)
BUSY: dict[int | str, dict[str, Any]] = {
    **NOT_FOUND, 409: {"model": ErrorBody, "description": "Recording already, or still (recording_busy)"},
    403: {"model": ErrorBody, "description": "The server's token was not given (forbidden)"}}
READ: dict[int | str, dict[str, Any]] = {
    **BUSY, 422: {"model": ErrorBody, "description": "The file cannot be read: cut short, changed "
                                                     "(recording_damaged, naming why)"}}


@router.post("/scenes/{scene}/recordings", status_code=201, responses=BUSY,
             summary="Start recording a scene (one recording at a time): answers its id")
async def start(request: Request, scene: str) -> dict[str, Any]:
    """Everything viewers are sent and every request clients make, with their times, into
    an MCAP file, until ``POST /api/recordings/{id}/stop``, a limit (``recordingBytes``,
    ``recordingSeconds``) or the scene's end. Needs the control token, as imports do."""
    changing_allowed(request)
    hubs = hubs_of(request)
    hub = hub_of(request, scene)
    recording_id, path = hubs.recordings.new(scene)
    answer = await hub.runner.call(Record(recording_id, str(path)))
    hubs.recordings.started(recording_id, scene)
    return answer


@router.post("/recordings/{recording_id}/stop", responses=BUSY,
             summary="Stop a recording: what it holds (bytes, seconds, ticks, requests, readings)")
async def stop(request: Request, recording_id: str) -> dict[str, Any]:
    changing_allowed(request)
    hubs = hubs_of(request)
    scene = hubs.recordings.recording(recording_id)  # unknown_recording for what was never made
    if scene is None:
        return hubs.recordings.describe(recording_id)  # stopped already: as it is
    # (a cluster's other gateway may have started it: this one attaches to its scene)
    answer = await (hubs.get(scene) or hubs.open(scene)).runner.call(Unrecord(recording_id))
    hubs.recordings.ended(recording_id)
    return answer


@router.post("/recordings/{recording_id}/resimulate", responses=READ,
             summary="Run a recording's requests again in a new scene; where the run differs")
async def resimulate(request: Request, recording_id: str, tolerance: float = 0.0) -> dict[str, Any]:
    """The scene the recording started from is made anew, its requests are applied and its
    ticks ticked as recorded, in a process of its own; the report counts the ticks that
    differ by more than ``tolerance`` and lists the first differences (``tick``, ``time``,
    ``field``, ``id``, ``recorded``, ``now``). Kinematic mode: none."""
    changing_allowed(request)  # minutes of a core, maybe
    hubs = hubs_of(request)
    path = hubs.recordings.readable(recording_id)
    if not 0 <= tolerance <= 1e6:
        raise OutOfRange(f"tolerance must be within [0, 1000000], got {tolerance}", argument="tolerance")
    return await hubs.resimulations.run(resimulate_file, str(path), hubs.limits, hubs.assets,
                                        tolerance, hubs.uploads,
                                        hung_up=hang_up_of(request))


@router.get("/recordings/{recording_id}/at", responses=READ,
            summary="A recording at a time (s from its start): a snapshot and one folded frame")
async def at(request: Request, recording_id: str, time: float = 0.0) -> dict[str, Any]:
    """What a player shows after a seek: ``time`` (clamped), ``duration`` and the
    ``messages`` that make the scene as it was then."""
    hubs = hubs_of(request)
    path = hubs.recordings.readable(recording_id)
    return await hubs.replays.run(replay.seek, str(path), _seconds(time, "time"),
                                  hung_up=hang_up_of(request))


@router.get("/recordings/{recording_id}/ticks", responses=READ,
            summary="A recording's ticks in (after, until], at most 10 s of them: [time, messages] each")
async def ticks(request: Request, recording_id: str, after: float, until: float) -> dict[str, Any]:
    hubs = hubs_of(request)
    path = hubs.recordings.readable(recording_id)
    start, end = _seconds(after, "after"), _seconds(until, "until")
    if not 0 <= end - start <= WINDOW_SECONDS:
        raise OutOfRange(f"until - after must be within [0, {WINDOW_SECONDS}] s, got {end - start:g}",
                         argument="until")
    return await hubs.replays.run(replay.window, str(path), start, end,
                                  hung_up=hang_up_of(request))


def _seconds(value: float, name: str) -> float:
    if not math.isfinite(value) or not -1e9 <= value <= 1e9:
        raise OutOfRange(f"{name} must be a number of seconds, got {value}", argument=name)
    return value


@router.get("/recordings", summary="Every recording, newest first: its scene, state, size, "
                                   "start, duration and messages")
async def listing(request: Request) -> list[dict[str, Any]]:
    return hubs_of(request).recordings.listing()


@router.get("/recordings/{recording_id}", responses=BUSY, response_class=FileResponse,
            summary="A finished recording's MCAP file (Foxglove opens it)")
async def download(request: Request, recording_id: str) -> FileResponse:
    path = hubs_of(request).recordings.finished(recording_id)
    return FileResponse(path, media_type="application/octet-stream", filename=path.name)
