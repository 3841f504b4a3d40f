"""The server's scenes by name (real scene processes, driven without sockets)."""

from __future__ import annotations

import asyncio
import json
from pathlib import Path

from server.core.operations import Operations
from server.core.scene import Scene
from server.core.scene_document import export_scene
from server.web.hub import Hubs, clients_objects
from server.web.state_dir import StateDir


def document_with_boxes(count: int) -> dict:
    scene = Scene("made")
    ops = Operations(scene, "c7")
    for k in range(count):
        ops.create(f"c7.{k}", "Box", [])
    try:
        return export_scene(scene)
    finally:
        scene.close()


def test_a_saved_scene_opened_again_while_it_stops_gets_its_last_change(tmp_path: Path) -> None:
    """Stopped less than a second after a change (not saved yet but on stopping), then
    opened at once: the new process waits for the old one's final save."""
    async def scenario() -> tuple[int, int]:
        hubs = Hubs(state=StateDir(tmp_path))
        try:
            first = hubs.open("lab")
            await first.runner.call("import", document_with_boxes(400))
            assert await hubs.remove_idle(float("inf")) == ["lab"]
            again = hubs.open("lab")
            held = json.loads(await again.runner.call("read", clients_objects, ()))
            return held, again.runner.pid != first.runner.pid
        finally:
            await hubs.stop()
    assert asyncio.run(scenario()) == (400, True)
