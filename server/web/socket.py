"""The /ws endpoint: moves text between a WebSocket and a sans-I/O :class:`Session`."""

from __future__ import annotations

import asyncio
import logging

from fastapi import APIRouter, WebSocket
from starlette.websockets import WebSocketDisconnect

from ..core.physics import ENGINE
from ..core.session import ROLES, Session
from ..errors import OutOfRange, VPError
from .hub import Connection, Hubs
from .outbox import Outgoing

log = logging.getLogger(__name__)
router = APIRouter()
POLICY_VIOLATION = 1008


@router.websocket("/ws")
async def websocket_endpoint(websocket: WebSocket, scene: str = "default",
                             role: str = "controller", engine: str = ENGINE) -> None:
    hubs: Hubs = websocket.app.state.hubs
    await websocket.accept()
    try:
        if role not in ROLES:
            raise OutOfRange(f"role must be controller or viewer, got {role!r}", role=role)
        if engine != ENGINE:
            raise OutOfRange(f"engine {engine!r} is not available; this server runs {ENGINE}",
                             engine=engine)
        hub = hubs.open(scene)
    except VPError as error:
        await websocket.send_text(Outgoing.of(error.to_wire()).text)
        await websocket.close(POLICY_VIOLATION, error.message[:120])
        return
    connection = Connection(Session(hub.scene, hubs.new_client_id(), role))
    hub.join(connection)
    writer = asyncio.create_task(_write(websocket, connection))
    reader = asyncio.create_task(_read(websocket, connection))
    closed = asyncio.create_task(connection.closed.wait())
    try:
        await asyncio.wait({writer, reader, closed}, return_when=asyncio.FIRST_COMPLETED)
    finally:
        for task in (writer, reader, closed):
            task.cancel()
        hub.leave(connection)
        await _close_quietly(websocket)


async def _read(websocket: WebSocket, connection: Connection) -> None:
    session = connection.session
    while True:
        event = await websocket.receive()
        if event["type"] == "websocket.disconnect":
            return
        text = event.get("text")
        if text is None:
            text = (event.get("bytes") or b"").decode("utf-8", errors="replace")
        for answer in session.receive(text):
            connection.send(Outgoing.of(answer))


async def _write(websocket: WebSocket, connection: Connection) -> None:
    try:
        while True:
            item = await connection.outbox.get()
            await websocket.send_text(item.text)
    except (WebSocketDisconnect, RuntimeError):
        return


async def _close_quietly(websocket: WebSocket) -> None:
    try:
        await websocket.close()
    except (RuntimeError, WebSocketDisconnect):
        pass
