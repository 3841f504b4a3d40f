"""REST routes: read-only inspection of the running scenes (documented at /docs).

Whatever reads a scene runs on that scene's thread, between its ticks, and is encoded
there too (:func:`_read`): a large scene costs the event loop nothing.
"""

from __future__ import annotations

import time
from typing import Any, Callable

from fastapi import APIRouter, Request, Response
from fastapi.responses import JSONResponse

from ..core import reports
from ..core.messages import PROTOCOL_VERSION, encode
from ..core.robot import Robot
from ..core.scene import Scene
from ..core.sensor import Sensor
from ..core.wire import encode_numbers
from ..errors import UnknownObject, UnknownScene, VPError
from .hub import Hubs, SceneHub

router = APIRouter(prefix="/api")
VERSION = "0.1.0"


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


async def _read(request: Request, scene: str, report: Callable[[Scene], Any]) -> Response:
    """``report`` of a scene, computed and encoded as JSON on the scene's thread."""
    hub = _hub(request, scene)
    body = await hub.runner.call(lambda: encode(encode_numbers(report(hub.scene))))
    return Response(body, media_type="application/json")


async def _summary(hub: SceneHub) -> dict[str, Any]:
    viewers = sum(c.session.role == "viewer" for c in hub.connections)
    summary = await hub.runner.call(lambda: reports.scene_summary(hub.scene))
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


@router.get("/scenes/{scene}", summary="One scene: clock, counts, camera")
async def scene_detail(request: Request, scene: str) -> dict[str, Any]:
    return await _summary(_hub(request, scene))


@router.get("/scenes/{scene}/snapshot", summary="The whole scene, as the WebSocket snapshot",
            response_class=Response)
async def snapshot(request: Request, scene: str) -> Response:
    return await _read(request, scene, Scene.snapshot)


@router.get("/scenes/{scene}/robots", summary="The robots of a scene", response_class=Response)
async def robot_list(request: Request, scene: str) -> Response:
    return await _read(request, scene,
                       lambda s: [reports.robot_summary(r) for r in reports.robots(s)])


@router.get("/scenes/{scene}/robots/{robot_id}", response_class=Response,
            summary="A robot: position, rotation, parts and motors in motor order")
async def robot_detail(request: Request, scene: str, robot_id: str) -> Response:
    def report(s: Scene) -> dict[str, Any]:
        node = s.nodes.get(robot_id)
        if not isinstance(node, Robot):
            raise UnknownObject(f"no robot {robot_id[:80]!r} in scene {scene!r}",
                                object=robot_id)
        return reports.robot_report(node)
    return await _read(request, scene, report)


@router.get("/scenes/{scene}/sensors/{sensor_id:path}", response_class=Response,
            summary="A sensor's readings now: distance, touch, position, collision, objects "
                    "(and object, with ?other=<id>)")
async def sensor_detail(request: Request, scene: str, sensor_id: str,
                        other: str | None = None) -> Response:
    def report(s: Scene) -> dict[str, Any]:
        node = s.nodes.get(sensor_id)
        if not isinstance(node, Sensor):
            raise UnknownObject(f"no sensor {sensor_id[:80]!r} in scene {scene!r}",
                                object=sensor_id)
        return reports.sensor_report(node, other)
    return await _read(request, scene, report)


@router.get("/scenes/{scene}/contacts", summary="The pairs of parts (and ground) touching now",
            response_class=Response)
async def contacts(request: Request, scene: str) -> Response:
    return await _read(request, scene, reports.contacts_report)


@router.get("/metrics", summary="Tick timing, connections and queue lengths per scene")
async def metrics(request: Request) -> dict[str, Any]:
    hubs = _hubs(request)
    return {"scenesRemoved": hubs.removed,
            "scenes": {name: {"tickRate": hub.tick_rate, "ticks": hub.runner.stats.count,
                              "tickFailures": hub.runner.stats.failures,
                              **hub.runner.stats.summary(),
                              "clients": len(hub.connections),
                              "queued": sum(len(c.outbox) for c in hub.connections),
                              "queuedBytes": sum(c.outbox.bytes for c in hub.connections),
                              "framesMerged": sum(c.outbox.merged for c in hub.connections)}
                       for name, hub in hubs.scenes.items()}}
