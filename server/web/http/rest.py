"""REST routes: read-only inspection of the running scenes (documented at /docs).

Whatever reads a scene runs in that scene's process, between its ticks, and is encoded
there too (:func:`_read`): a large scene costs the event loop nothing. The functions
that read travel to the process by name, so they are defined at the top level here.
"""

from __future__ import annotations

import asyncio
import json
import time
from typing import Any, Callable, Literal

from fastapi import APIRouter, Request, Response
from fastapi.responses import JSONResponse

from ...core.model.robot import Robot
from ...core.model.sensor import Sensor
from ...core.physics.urdf_file import file_stem
from ...core.protocol import reports, robot_files
from ...core.protocol.messages import PROTOCOL_VERSION
from ...core.protocol.scene_document import check_document_bytes, export_scene
from ...core.scene.scene import Scene
from ...core.kit.errors import UnknownObject, UnknownScene, VPError
from . import prometheus
from .access import changing_allowed
from .rest_base import NOT_FOUND, ErrorBody, hub_of, hubs_of, read_body
from ..scenes.offload import hang_up_of
from ..scenes.scene_hub import SceneHub
from ..process.messages import Import, Metrics, Question, Read

router = APIRouter(prefix="/api")
VERSION = "0.1.0"
ANSWER_SECONDS = 1.0  # what lists and metrics wait for one scene before using its last answer
FILE_OR_NOT_FOUND: dict[int | str, dict[str, Any]] = {
    **NOT_FOUND, 200: {"content": {"application/octet-stream": {}}, "description": "The file"}}


async def _within(hub: SceneHub, question: Question) -> Any:
    """A scene's answer, or None when it has ended or has not answered in ANSWER_SECONDS
    (stopped, or working through a backlog): one scene never holds up a whole list."""
    if hub.ended:
        return None
    try:
        return await asyncio.wait_for(hub.runner.call(question), ANSWER_SECONDS)
    except (asyncio.TimeoutError, UnknownScene):
        return None


async def _read(request: Request, scene: str, report: Callable[..., Any],
                *args: Any) -> Response:
    """``report(scene, *args)``, computed and encoded as JSON in the scene's process."""
    body = await hub_of(request, scene).runner.call(Read(report, args))
    return Response(body, media_type="application/json")


async def _summary(hub: SceneHub, wait: bool = False) -> dict[str, Any]:
    """A scene's counts; from its last answer (``state`` says why) when it does not answer
    in time, unless ``wait``."""
    viewers = sum(c.role == "viewer" for c in hub.connections)
    if wait:
        hub.summary = json.loads(await hub.runner.call(Read(reports.scene_summary)))
    else:
        answer = await _within(hub, Read(reports.scene_summary))
        if answer is not None:
            hub.summary = json.loads(answer)
    return {"name": hub.name, **(hub.summary or {}), "state": hub.state,
            "clients": len(hub.connections), "viewers": viewers,
            "controllers": len(hub.connections) - viewers, "tickRate": hub.tick_rate}


@router.get("/health", summary="Is the server up, and what is failing")
async def health(request: Request) -> dict[str, Any]:
    """``status`` is ``ok``, or ``degraded`` with ``problems`` saying what fails: a scene
    that failed or is silent, changes that cannot be saved, a state folder that cannot be
    written. Answered at once, without asking any scene."""
    hubs = hubs_of(request)
    problems = hubs.problems()
    return {"status": "degraded" if problems else "ok", "problems": problems,
            "version": VERSION, "protocol": PROTOCOL_VERSION,
            "uptime": time.monotonic() - request.app.state.started, "scenes": len(hubs.scenes)}


@router.get("/scenes", summary="Every running scene with its robot and client counts "
                               "(saved=true adds the saved scenes that are not running)")
async def scenes(request: Request, saved: bool = False) -> list[dict[str, Any]]:
    hubs = hubs_of(request)
    running = list(hubs.scenes.values())
    listed = list(await asyncio.gather(*(_summary(hub) for hub in running)))
    if saved and hubs.state is not None:
        names = {hub.name for hub in running}
        listed += [{"name": name, "state": "saved"} for name in hubs.state.saved_scenes()
                   if name not in names]
    return listed


@router.get("/scenes/{scene}", responses=NOT_FOUND, summary="One scene: clock, counts, camera, physics")
async def scene_detail(request: Request, scene: str) -> dict[str, Any]:
    return await _summary(hub_of(request, scene), wait=True)


@router.get("/scenes/{scene}/snapshot", responses=NOT_FOUND, summary="The whole scene, as the WebSocket snapshot",
            response_class=Response)
async def snapshot(request: Request, scene: str) -> Response:
    return await _read(request, scene, Scene.snapshot)


@router.get("/scenes/{scene}/robots", responses=NOT_FOUND, summary="The robots of a scene", response_class=Response)
async def robot_list(request: Request, scene: str) -> Response:
    return await _read(request, scene, _robots)


@router.get("/scenes/{scene}/robots/{robot_id}", responses=NOT_FOUND, response_class=Response,
            summary="A robot: position, rotation, parts and motors in motor order")
async def robot_detail(request: Request, scene: str, robot_id: str) -> Response:
    return await _read(request, scene, _robot, robot_id)


@router.get("/scenes/{scene}/robots/{robot_id}/urdf", responses=FILE_OR_NOT_FOUND, response_class=Response,
            summary="A robot as a URDF zip: robot.urdf (links, joints, limits, inertials) and its meshes")
async def robot_urdf(request: Request, scene: str, robot_id: str) -> Response:
    """Written from the tree the physics compiles; the base at the file's origin (load it
    at the robot's position and rotation), joints named by their motors' ids."""
    return await _file(request, scene, robot_files.packed_urdf_job, robot_id, "application/zip", "zip")


@router.get("/scenes/{scene}/robots/{robot_id}/mjcf", responses=FILE_OR_NOT_FOUND, response_class=Response,
            summary="A robot as an MJCF zip: robot.xml (bodies, hinges, limits, inertials, couplings, "
                    "a position actuator per leading motor) and its meshes, for MuJoCo")
async def robot_mjcf(request: Request, scene: str, robot_id: str) -> Response:
    """Written from the tree the physics compiles, as the URDF is; followers as joint
    equalities. It compiles in MuJoCo (``mujoco.MjModel.from_xml_path``)."""
    return await _file(request, scene, robot_files.packed_mjcf_job, robot_id, "application/zip", "mjcf.zip")


@router.get("/scenes/{scene}/robots/{robot_id}/glb", responses=FILE_OR_NOT_FOUND, response_class=Response,
            summary="A robot's look as a GLB: its parts' meshes, colours and poses as they are now")
async def robot_glb(request: Request, scene: str, robot_id: str) -> Response:
    return await _file(request, scene, robot_files.packed_glb_job, robot_id, "model/gltf-binary", "glb")


async def _file(request: Request, scene: str, job: Callable[..., bytes], robot_id: str,
                media_type: str, suffix: str) -> Response:
    """A file taken from the scene (quick, in its process) and written beside it (in the
    process for files: the scene ticks on meanwhile), sent as a download named after the
    robot."""
    hubs = hubs_of(request)
    packed = await hub_of(request, scene).runner.call(Read(job, (robot_id,)))
    body = await hubs.files.run(robot_files.written, packed, hubs.assets,
                                hung_up=hang_up_of(request))
    return Response(body, media_type=media_type, headers={
        "Content-Disposition": f'attachment; filename="{file_stem(robot_id)}.{suffix}"'})


@router.get("/scenes/{scene}/sensors/{sensor_id:path}", responses=NOT_FOUND, response_class=Response,
            summary="A sensor's readings now: distance, touch, position, collision, objects "
                    "(and object, with ?other=<id>)")
async def sensor_detail(request: Request, scene: str, sensor_id: str,
                        other: str | None = None) -> Response:
    return await _read(request, scene, _sensor, sensor_id, other)


@router.get("/scenes/{scene}/contacts", responses=NOT_FOUND, summary="The pairs of parts (and ground) touching now",
            response_class=Response)
async def contacts(request: Request, scene: str) -> Response:
    return await _read(request, scene, reports.contacts_report)


@router.get("/scenes/{scene}/export", responses=NOT_FOUND, response_class=Response,
            summary="The scene as a versioned JSON document (POST it to import to restore it)")
async def export(request: Request, scene: str,
                 assets: Literal["embed", "refer"] = "embed") -> Response:
    """Structure, angles, poses, names, recolours, owners and the uploaded mesh files it
    uses, by content hash (``assets=embed``: with their bytes, so that any server can
    import it; ``refer``: by hash alone). No clock: an unchanged scene gives the same bytes."""
    body = await hub_of(request, scene).runner.call(Read(_export, (assets == "embed",)))
    return Response(body, media_type="application/json",
                    headers={"Content-Disposition": f'attachment; filename="{scene}.json"'})


IMPORTED: dict[int | str, dict[str, Any]] = {
    400: {"model": ErrorBody, "description": "Not a scene document, or one that fails a check "
                                             "(the scene is unchanged)"},
    403: {"model": ErrorBody, "description": "The server's token was not given, a page of "
                                             "another site sent it, or it would take what "
                                             "connected clients own (forbidden)"},
    413: {"model": ErrorBody, "description": "Larger than the documentBytes limit (too_large)"},
    429: {"model": ErrorBody, "description": "A limit of the scene or server (limit_exceeded)"}}
DOCUMENT_BODY = {"requestBody": {"required": True, "description": "what export gave", "content": {
    "application/json": {"schema": {"type": "object"}}}}}


@router.post("/scenes/{scene}/import", responses=IMPORTED, openapi_extra=DOCUMENT_BODY,
             summary="Replace a scene (made if needed) by a document export gave")
async def import_(request: Request, scene: str, replace: bool = False) -> JSONResponse:
    """Everything in the scene is replaced: its connected clients get a warning and a new
    snapshot; owners of imported objects who are not connected have ``leaveGraceSeconds`` to
    come back (what they keep stays). Refused (``forbidden``) when clients connected to the
    scene own objects in it (``replace=true`` replaces them anyway) or in the document (it
    would make those theirs). A document that fails any check changes nothing. With a
    server token, ``Authorization: Bearer <token>`` is needed; pages of other sites may not.
    The document is read and checked in the scene's process: no other scene waits."""
    changing_allowed(request)
    hubs = hubs_of(request)
    body = await read_body(request, hubs.limits.document_bytes, "documentBytes", "the document")
    made = (hubs.get(scene) is None or hubs.scenes[scene].ended) and not (
        hubs.state is not None and scene in hubs.state.saved_scenes())
    if made:  # checked before a scene's process is started for it (in the checking process)
        await hubs.offload.run(check_document_bytes, body)
    hub = hub_of(request, scene) if not made else hubs.open(scene)
    try:
        async with hub.importing():  # no newcomer gets an id the document brings meanwhile
            summary = json.loads(await hub.runner.call(Import(body, replace)))
            hubs.reserve(summary["owners"])
    except VPError:
        if made:
            hubs.discard(hub)  # a refused document leaves no scene behind
        raise
    return JSONResponse(summary)


def _export(scene: Scene, embed: bool) -> dict[str, Any]:
    return export_scene(scene, embed_assets=embed)


@router.get("/metrics", responses={200: {"content": {"application/json": {}, "text/plain": {}}}},
            summary="Per scene, over the last 10 s: tick duration p50/p95/max, "
                                 "ticks, requests and CPU per second, peak contact force; totals, connections and "
                                 "queues (format=prometheus: Prometheus's text format)")
async def metrics(request: Request, format: Literal["json", "prometheus"] = "json") -> Any:
    hubs = hubs_of(request)
    running = list(hubs.scenes.items())
    figures = {"scenesRemoved": hubs.removed, "scenes": dict(zip(
        [name for name, _ in running],
        await asyncio.gather(*(_scene_metrics(hub) for _, hub in running))))}
    if format == "prometheus":
        return Response(prometheus.exposition(figures), media_type=prometheus.CONTENT_TYPE)
    return figures


async def _scene_metrics(hub: SceneHub) -> dict[str, Any]:
    """A scene's figures; its last ones (``state`` says why) when it does not answer in time."""
    stats = await _within(hub, Metrics())
    if stats is not None:
        hub.figures = stats
    return {"tickRate": hub.tick_rate, **(hub.figures or {}), "state": hub.state,
            "silentSeconds": round(hub.silent, 3), "asleep": hub.asleep, "pid": hub.runner.pid,
            "clients": len(hub.connections),
            "queued": sum(len(c.outbox) for c in hub.connections),
            "queuedBytes": sum(c.outbox.bytes for c in hub.connections),
            "framesMerged": sum(c.outbox.merged for c in hub.connections),
            "viewerFrames": hub.viewer_frames, "fanoutCpuSeconds": round(hub.fanout_cpu, 6)}


def _robots(scene: Scene) -> list[dict[str, Any]]:
    return [reports.robot_summary(robot) for robot in reports.robots(scene)]


def _robot(scene: Scene, robot_id: str) -> dict[str, Any]:
    node = scene.nodes.get(robot_id)
    if not isinstance(node, Robot):
        raise UnknownObject(f"no robot {robot_id[:80]!r} in scene {scene.name!r}",
                            object=robot_id)
    return reports.robot_report(node)


def _sensor(scene: Scene, sensor_id: str, other: str | None) -> dict[str, Any]:
    node = scene.nodes.get(sensor_id)
    if not isinstance(node, Sensor):
        raise UnknownObject(f"no sensor {sensor_id[:80]!r} in scene {scene.name!r}",
                            object=sensor_id)
    return reports.sensor_report(node, other)
