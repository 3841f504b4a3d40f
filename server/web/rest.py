"""REST routes: read-only inspection of the running scenes (documented at /docs).

Whatever reads a scene runs in that scene's process, between its ticks, and is encoded
there too (:func:`_read`): a large scene costs the event loop nothing. The functions
that read travel to the process by name, so they are defined at the top level here.
"""

from __future__ import annotations

import json
import time
from typing import Any, Callable, Literal

from fastapi import APIRouter, Request, Response
from fastapi.responses import JSONResponse
from pydantic import BaseModel

from ..core import reports
from ..core.messages import PROTOCOL_VERSION
from ..core.robot import Robot
from ..core.scene import Scene
from ..core.sensor import Sensor
from ..errors import UnknownObject, UnknownScene, VPError
from . import prometheus
from .hub import Hubs, SceneHub

router = APIRouter(prefix="/api")
VERSION = "0.1.0"


class ErrorBody(BaseModel):
    """What a refused REST request gets: the same code and message as on the WebSocket."""

    code: str
    message: str
    details: dict[str, Any] | None = None


NOT_FOUND: dict[int | str, dict[str, Any]] = {
    404: {"model": ErrorBody, "description": "No such scene (or robot, sensor, object)"}}


def error_response(error: VPError, status: int) -> JSONResponse:
    """A structured error body: the same code and message as on the WebSocket."""
    wire = error.to_wire()
    body = {"code": wire["code"], "message": wire["message"]}
    if error.details:
        body["details"] = wire["details"]
    return JSONResponse(body, status_code=status)


def _hubs(request: Request) -> Hubs:
    return request.app.state.hubs


def _hub(request: Request, scene: str) -> SceneHub:
    hub = _hubs(request).get(scene)
    if hub is None:
        raise UnknownScene(f"no scene named {scene[:80]!r}", scene=scene)
    return hub


async def _read(request: Request, scene: str, report: Callable[..., Any],
                *args: Any) -> Response:
    """``report(scene, *args)``, computed and encoded as JSON in the scene's process."""
    body = await _hub(request, scene).runner.call("read", report, args)
    return Response(body, media_type="application/json")


async def _summary(hub: SceneHub) -> dict[str, Any]:
    viewers = sum(c.role == "viewer" for c in hub.connections)
    summary = json.loads(await hub.runner.call("read", reports.scene_summary, ()))
    return {**summary, "clients": len(hub.connections), "viewers": viewers,
            "controllers": len(hub.connections) - viewers, "tickRate": hub.tick_rate}


@router.get("/health", summary="Is the server up")
async def health(request: Request) -> dict[str, Any]:
    hubs = _hubs(request)
    return {"status": "ok", "version": VERSION, "protocol": PROTOCOL_VERSION,
            "uptime": time.monotonic() - request.app.state.started, "scenes": len(hubs.scenes)}


@router.get("/scenes", summary="Every scene with its robot and client counts")
async def scenes(request: Request) -> list[dict[str, Any]]:
    return [await _summary(hub) for hub in list(_hubs(request).scenes.values())]


@router.get("/scenes/{scene}", responses=NOT_FOUND, summary="One scene: clock, counts, camera")
async def scene_detail(request: Request, scene: str) -> dict[str, Any]:
    return await _summary(_hub(request, scene))


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


@router.get("/metrics", responses={200: {"content": {"application/json": {}, "text/plain": {}}}},
            summary="Per scene, over the last 10 s: tick duration p50/p95/max, "
                                 "ticks, requests and CPU per second; totals, connections and "
                                 "queues (format=prometheus: Prometheus's text format)")
async def metrics(request: Request, format: Literal["json", "prometheus"] = "json") -> Any:
    hubs = _hubs(request)
    figures = {"scenesRemoved": hubs.removed,
               "scenes": {name: await _scene_metrics(hub) for name, hub in list(hubs.scenes.items())}}
    if format == "prometheus":
        return Response(prometheus.exposition(figures), media_type=prometheus.CONTENT_TYPE)
    return figures


async def _scene_metrics(hub: SceneHub) -> dict[str, Any]:
    stats = await hub.runner.call("metrics")
    return {"tickRate": hub.tick_rate, **stats, "pid": hub.runner.pid,
            "clients": len(hub.connections),
            "queued": sum(len(c.outbox) for c in hub.connections),
            "queuedBytes": sum(c.outbox.bytes for c in hub.connections),
            "framesMerged": sum(c.outbox.merged for c in hub.connections)}


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
