"""Every bound the server enforces, with its default: the one place they are defined.

A limit that is reached is refused with ``limit_exceeded`` naming it (``details.limit``
is the wire name below, ``details.value`` its value). The server sends all of them in
``hello``; ``vp-server --limit name=value`` changes one (either spelling works).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, fields, replace
from typing import Any

# Figures of single values, not configurable: they keep the geometry computable.
MIN_SIZE = 0.001         # metres: the smallest size of a part (a radius, a side, a length)
MAX_SIZE = 1000.0        # metres: the largest
MAX_COORDINATE = 100_000.0  # metres: the largest |x|, |y| or |z| of a position or slot


@dataclass(frozen=True)
class Limits:
    """The configurable limits (wire names are these names in camelCase)."""

    # one WebSocket text message
    message_bytes: int = 1 << 20          # UTF-8 bytes of one text message
    messages_per_text: int = 10_000       # request objects in one array
    batch_ops: int = 10_000               # operations in one batch
    # one connection
    bytes_per_second: int = 16 << 20      # text received per second
    outbox_bytes: int = 32 << 20          # waiting to be sent; past it the connection closes
    # one client in a scene
    client_objects: int = 10_000          # objects it made that exist, inner parts included
    client_names: int = 1_000             # non-numeric ids (c7.arm) it may use in a scene
    # one scene
    scene_objects: int = 20_000           # objects (nodes) of all clients
    scene_bodies: int = 2_000             # collision bodies (physical parts in the scene)
    tree_depth: int = 256                 # nodes from a root to its deepest descendant
    watched_sensors: int = 1_000
    contact_tests: int = 2_000            # pair tests per tick; more wait for later ticks
    contact_pairs: int = 32_000           # touching pairs recorded at once
    saved_states: int = 16                # states saveState keeps (forgetState frees one)
    # one SceneMesh (a mesh a page added to its scene)
    shape_vertices: int = 10_000          # vertices of its geometry
    shape_triangles: int = 20_000         # triangles of a triangle mesh
    transforms_per_call: int = 10_000     # objects one setTransforms places
    # the server
    scenes: int = 100                     # vp-server's default: what the machine's memory
                                          # holds (server/web/scenes/scene_capacity.py)
    scene_idle_seconds: int = 60          # a scene without clients is removed after this
    leave_grace_seconds: int = 10         # a client that left gets its objects back this long
    connections: int = 1_000
    connections_per_address: int = 256
    header_seconds: int = 10              # to send a complete HTTP request head
    header_bytes: int = 16_384            # size of an HTTP request head
    # uploaded mesh files (POST /api/assets)
    asset_bytes: int = 8 << 20            # one file
    asset_triangles: int = 200_000        # triangles of one file's mesh
    assets: int = 1_000                   # files kept
    # an uploaded robot (POST /api/scenes/{scene}/robots): a zip or a bare URDF/MJCF
    robot_bytes: int = 64 << 20           # the upload, and its zip's files inflated
    robot_files: int = 2_000              # files in its zip
    robot_triangles: int = 1_000_000      # triangles of all its meshes
    # a scene document (POST /api/scenes/{scene}/import), its files' bytes included
    document_bytes: int = 64 << 20
    # a recording (POST /api/scenes/{scene}/recordings): it stops itself at either
    recording_bytes: int = 256 << 20      # its file
    recording_seconds: int = 3_600        # scene time it covers
    # the recordings kept: when a new one starts, the oldest finished ones go until fewer
    # than this many are kept and their bytes are under recordingsBytes
    recordings: int = 200
    recordings_bytes: int = 4 << 30
    # work beside the scenes, each kind in a process of its own (server/web/scenes/offload.py):
    # what runs or waits at once; more is refused (busy) until some is done
    file_jobs: int = 8                    # robot files (URDF, GLB) being written
    resimulations: int = 2                # recordings run again
    replay_reads: int = 32                # seeks and windows of recordings for players

    def wire(self) -> dict[str, int]:
        """The limits by wire name, as ``hello`` carries them."""
        return {camel(f.name): getattr(self, f.name) for f in fields(self)}

    def with_values(self, assignments: list[str]) -> Limits:
        """A copy with ``name=value`` assignments applied (names in either spelling)."""
        names = {camel(f.name): f.name for f in fields(self)} | {f.name: f.name for f in fields(self)}
        changes: dict[str, Any] = {}
        for assignment in assignments:
            name, _, value = assignment.partition("=")
            if name not in names or not value.isdigit() or int(value) < 1:
                raise ValueError(f"expected NAME=N (N ≥ 1) with NAME one of "
                                 f"{', '.join(sorted(self.wire()))}; got {assignment!r}")
            changes[names[name]] = int(value)
        return replace(self, **changes)


def camel(name: str) -> str:
    """``scene_objects`` → ``sceneObjects``."""
    return re.sub(r"_([a-z])", lambda m: m.group(1).upper(), name)


DEFAULT = Limits()
