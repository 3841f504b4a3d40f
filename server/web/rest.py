"""REST routes: read-only inspection of the running scenes (documented at /docs).

Handlers are ``async def`` on purpose: they then run on the event loop, between ticks,
never in a worker thread beside the tick.
"""

from __future__ import annotations

import time
from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse

from ..core import reports
from ..core.messages import PROTOCOL_VERSION
from ..core.robot import Robot
from ..core.sensor import Sensor
from ..errors import UnknownObject, UnknownScene, VPError
from .hub import Hubs, SceneHub

router = APIRouter(prefix="/api")
VERSION = "0.1.0"


def error_response(error: VPError, status: int) -> JSONResponse:
    """A structured error body: the same code and message as on the WebSocket."""
    body = {"code": error.code, "message": error.message}
    if error.details:
        body["details"] = error.details
    return JSONResponse(body, status_code=status)


def _hubs(request: Request) -> Hubs:
    return request.app.state.hubs


def _hub(request: Request, scene: str) -> SceneHub:
    hub = _hubs(request).get(scene)
    if hub is None:
        raise UnknownScene(f"no scene named {scene!r}", scene=scene)
    return hub


def _summary(hub: SceneHub) -> dict[str, Any]:
    viewers = sum(c.session.role == "viewer" for c in hub.connections)
    return {**reports.scene_summary(hub.scene), "clients": len(hub.connections),
            "viewers": viewers, "controllers": len(hub.connections) - viewers,
            "tickRate": hub.tick_rate}


@router.get("/health", summary="Is the server up")
async def health(request: Request) -> dict[str, Any]:
    hubs = _hubs(request)
    return {"status": "ok", "version": VERSION, "protocol": PROTOCOL_VERSION,
            "uptime": time.monotonic() - request.app.state.started, "scenes": len(hubs.scenes)}


@router.get("/scenes", summary="Every scene with its robot and client counts")
async def scenes(request: Request) -> list[dict[str, Any]]:
    return [_summary(hub) for hub in _hubs(request).scenes.values()]


@router.get("/scenes/{scene}", summary="One scene: clock, counts, camera")
async def scene_detail(request: Request, scene: str) -> dict[str, Any]:
    return _summary(_hub(request, scene))


@router.get("/scenes/{scene}/snapshot", summary="The whole scene, as the WebSocket snapshot")
async def snapshot(request: Request, scene: str) -> dict[str, Any]:
    return _hub(request, scene).scene.snapshot()


@router.get("/scenes/{scene}/robots", summary="The robots of a scene")
async def robot_list(request: Request, scene: str) -> list[dict[str, Any]]:
    return [reports.robot_summary(r) for r in reports.robots(_hub(request, scene).scene)]


@router.get("/scenes/{scene}/robots/{robot_id}",
            summary="A robot: position, rotation, parts and motors in motor order")
async def robot_detail(request: Request, scene: str, robot_id: str) -> dict[str, Any]:
    node = _hub(request, scene).scene.nodes.get(robot_id)
    if not isinstance(node, Robot):
        raise UnknownObject(f"no robot {robot_id!r} in scene {scene!r}", object=robot_id)
    return reports.robot_report(node)


@router.get("/scenes/{scene}/sensors/{sensor_id:path}",
            summary="A sensor's readings now: distance, touch, position, collision, objects "
                    "(and object, with ?other=<id>)")
async def sensor_detail(request: Request, scene: str, sensor_id: str,
                        other: str | None = None) -> dict[str, Any]:
    node = _hub(request, scene).scene.nodes.get(sensor_id)
    if not isinstance(node, Sensor):
        raise UnknownObject(f"no sensor {sensor_id!r} in scene {scene!r}", object=sensor_id)
    return reports.sensor_report(node, other)


@router.get("/scenes/{scene}/contacts", summary="The pairs of parts (and ground) touching now")
async def contacts(request: Request, scene: str) -> dict[str, Any]:
    return reports.contacts_report(_hub(request, scene).scene)


@router.get("/metrics", summary="Tick timing, connections and queue lengths per scene")
async def metrics(request: Request) -> dict[str, Any]:
    return {"scenes": {name: {"tickRate": hub.tick_rate, "ticks": hub.stats.count,
                              "tickMsLast": hub.stats.last_ms, "tickMsMax": hub.stats.max_ms,
                              "tickMsMean": hub.stats.total_ms / max(1, hub.stats.count),
                              "clients": len(hub.connections),
                              "queued": sum(len(c.outbox) for c in hub.connections),
                              "framesMerged": sum(c.outbox.merged for c in hub.connections)}
                       for name, hub in _hubs(request).scenes.items()}}
