"""The /ws endpoint: moves text between a WebSocket and its scene's thread.

The reader hands each text to the scene (:meth:`SceneHub.receive`) and waits while too
much of this connection's text is still unapplied, so a flooding client is slowed by
TCP itself; it yields to the loop after every message, so texts already queued never
hold up other connections. The writer drains the connection's outbox.
"""

from __future__ import annotations

import asyncio
import logging

from fastapi import APIRouter, WebSocket
from starlette.websockets import WebSocketDisconnect

from ...core.physics.engine import ENGINE
from ...core.protocol.session import ROLES
from ...core.kit.errors import LimitExceeded, OutOfRange, VPError
from .access import AccessPolicy
from ..connections.framed_socket import framed_socket
from ..scenes.hub import Hubs
from ..connections.outbox import Outbox
from ..connections.outgoing import Outgoing
from ..scenes.scene_hub import Connection, SceneHub

log = logging.getLogger(__name__)
router = APIRouter()
POLICY_VIOLATION = 1008
TRY_AGAIN_LATER = 1013


@router.websocket("/ws")
async def websocket_endpoint(websocket: WebSocket, scene: str = "default",
                             role: str = "controller", engine: str = ENGINE,
                             token: str | None = None, resume: str | None = None,
                             keep: bool = False) -> None:
    hubs: Hubs = websocket.app.state.hubs
    access: AccessPolicy = websocket.app.state.access
    await websocket.accept()
    try:
        if role not in ROLES:
            raise OutOfRange(f"role must be controller or viewer, got {role[:40]!r}", role=role)
        access.check_origin(websocket.headers.get("origin"), websocket.headers.get("host"))
        access.check_role(role, token)
        if engine != ENGINE:
            raise OutOfRange(f"engine {engine[:40]!r} is not available; this server runs "
                             f"{ENGINE}", engine=engine)
        hub = hubs.open(scene)
        await hub.settled()  # restored (its owners reserved), no import under way
        await hubs.ids.available()  # a cluster's ids come from the bus
    except VPError as error:
        code = TRY_AGAIN_LATER if isinstance(error, LimitExceeded) else POLICY_VIOLATION
        await websocket.send_text(Outgoing.of(error.to_wire()).text)
        await websocket.close(code, error.message[:120])
        return
    client_id, resume_key = hubs.client_for(scene, resume)
    connection = Connection(client_id, role, Outbox(hubs.limits.outbox_bytes), resume_key, keep,
                            trusted=role == "controller" and access.trusts(token),
                            socket=framed_socket(websocket.scope))
    tasks: list[asyncio.Task[object]] = []
    try:
        await hub.join(connection)
        tasks = [asyncio.create_task(_write(websocket, connection)),
                 asyncio.create_task(_read(websocket, connection, hub)),
                 asyncio.create_task(connection.closed.wait())]
        await asyncio.wait(tasks, return_when=asyncio.FIRST_COMPLETED)
    except VPError as error:
        await websocket.send_text(Outgoing.of(error.to_wire()).text)
    finally:
        for task in tasks:
            task.cancel()
        hub.leave(connection)
        await _say_farewell(websocket, connection)
        await _close_quietly(websocket, connection.close_code, connection.close_reason)


async def _read(websocket: WebSocket, connection: Connection, hub: SceneHub) -> None:
    while True:
        event = await websocket.receive()
        if event["type"] == "websocket.disconnect":
            return
        text = event.get("text")
        hub.receive(connection, text if text is not None else event.get("bytes") or b"")
        if connection.drained.is_set():
            await asyncio.sleep(0)  # messages already received must not monopolise the loop
        else:
            await connection.drained.wait()


async def _write(websocket: WebSocket, connection: Connection) -> None:
    socket = connection.socket
    try:
        while True:
            item = await connection.take()  # until written: nothing may be written before it
            if socket is None:
                await websocket.send_text(item.text)
            else:
                await socket.write(item.frame)
            connection.written()
    except (WebSocketDisconnect, RuntimeError, OSError):  # (OSError: uvicorn's disconnect)
        return


async def _say_farewell(websocket: WebSocket, connection: Connection) -> None:
    if connection.farewell is not None:
        try:
            await asyncio.wait_for(websocket.send_text(connection.farewell.text), 2)
        except (asyncio.TimeoutError, RuntimeError, WebSocketDisconnect):
            pass


async def _close_quietly(websocket: WebSocket, code: int = 1000, reason: str = "") -> None:
    try:
        await websocket.close(code, reason)
    except (RuntimeError, WebSocketDisconnect):
        pass
