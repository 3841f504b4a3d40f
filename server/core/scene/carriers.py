"""Where the nodes that parts carry are.

A sensor on a fingertip is not a body: its frame is its part's frame in Bullet composed
with the sensor's offset from the part (one or two local poses), for all watched sensors
at once in numpy, as rotation matrices (the part's are at hand: the ray targets turn
rays by them; a sensor's ray is its matrix's second column). A node under a stretched
part or a motor is posed by its tree instead (:meth:`~server.core.model.node.Node.world_pose`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from ..kit import math3d
from ..kit.math3d import Pose, Vec3
from ..model.node import UNIT_SCALE, Node

FrameArrays = Callable[[tuple[str, ...]], "tuple[np.ndarray, np.ndarray]"]  # positions, matrices
CARRIED_SETS = 64  # sets of nodes whose carriers are kept (watched sensors: one set)


@dataclass(frozen=True)
class _Carried:
    """Nodes (by index in a list of them) that parts carry: the part carrying each and the
    node's offset from it; and the nodes posed by their tree instead (``own``)."""

    own: list[int]
    rows: np.ndarray
    hosts: tuple[str, ...]
    positions: np.ndarray  # n×3, in the part's frame
    turns: np.ndarray  # n×3×3, from the part's frame


class Carriers:
    """The parts with bodies (and their world scales), and what the parts carry; where
    the parts are comes from whoever asks (:meth:`world_frames`)."""

    def __init__(self) -> None:
        self._scales: dict[str, Vec3] = {}  # each part with a body: its world scale
        # node id -> the part carrying it and its offset from it (None: none); until a build
        self._offsets: dict[str, tuple[str, Pose] | None] = {}
        self._carried: dict[tuple[str, ...], _Carried] = {}  # node ids -> as world_frames needs
        self._hosts: dict[tuple[str, ...], list[str | None]] = {}  # sensor ids -> host_ids

    def built(self, keys: Sequence[str], scales: Sequence[Vec3]) -> None:
        """Parts with bodies now, at these world scales (a tree built again)."""
        self._scales.update(zip(keys, scales))

    def forget(self, keys: Sequence[str]) -> None:
        """Parts without a body any more: nothing is carried by them."""
        if keys:
            self.forget_offsets()
        for key in keys:
            self._scales.pop(key, None)

    def forget_offsets(self) -> None:
        """Trees were built again: offsets are worked out anew."""
        self._offsets.clear()
        self._carried.clear()
        self._hosts.clear()

    def host_ids(self, sensors: list[Node]) -> list[str | None]:
        """The id of the part whose contacts each sensor reports (``Sensor.host``; None:
        none), kept as the offsets are: a tick's watched sensors are one set, and walking
        up from each was a twentieth of sensing them."""
        key = tuple(sensor.id for sensor in sensors)
        found = self._hosts.get(key)
        if found is None:
            if len(self._hosts) >= CARRIED_SETS:
                self._hosts.clear()
            hosts = [sensor.host() for sensor in sensors]  # type: ignore[attr-defined]
            found = self._hosts[key] = [None if host is None else host.id for host in hosts]
        return found

    def world_frames(self, nodes: list[Node], part_frames: FrameArrays) -> tuple[np.ndarray, np.ndarray]:
        """World positions (n×3) and rotation matrices (n×3×3) of nodes: the frame in
        Bullet of the unscaled part that carries a node (``part_frames`` gives them as
        arrays, for parts by id), composed with the node's offset from it, for all such
        nodes at once; else the tree's own (:meth:`Node.world_pose`)."""
        key = tuple(node.id for node in nodes)
        carried = self._carried.get(key)
        if carried is None:
            if len(self._carried) >= CARRIED_SETS:
                self._carried.clear()
            carried = self._carried[key] = self._carriers(nodes)
        if carried.hosts:
            at, turn = part_frames(carried.hosts)
            hosted = np.einsum("kij,kj->ki", turn, carried.positions) + at, turn @ carried.turns
            if not carried.own:  # all carried, in order (as watched sensors on parts)
                return hosted
        positions, turns = np.empty((len(nodes), 3)), np.empty((len(nodes), 3, 3))
        for index in carried.own:
            position, quat = nodes[index].world_pose()
            positions[index], turns[index] = position, math3d.to_matrix(quat)
        if carried.hosts:
            positions[carried.rows], turns[carried.rows] = hosted
        return positions, turns

    def _carriers(self, nodes: list[Node]) -> _Carried:
        """Which of ``nodes`` their parts carry, and their offsets, as arrays."""
        found = [self._offset(node) for node in nodes]
        rows = [index for index, host in enumerate(found) if host is not None]
        offsets = [found[index][1] for index in rows]  # type: ignore[index]
        return _Carried(own=[index for index, host in enumerate(found) if host is None],
                        rows=np.array(rows, dtype=np.int64),
                        hosts=tuple(found[index][0] for index in rows),  # type: ignore[index]
                        positions=np.array([p for p, _ in offsets]).reshape(-1, 3),
                        turns=np.array([math3d.to_matrix(q) for _, q in offsets]).reshape(-1, 3, 3))

    def _offset(self, node: Node) -> tuple[str, Pose] | None:
        """The unscaled part that carries ``node`` and the node's pose relative to it; None
        when the tree's own pose must be used. Kept until a tree is built again (every
        change of a pose below a root, or of a parent, rebuilds its tree)."""
        if node.id in self._offsets:
            return self._offsets[node.id]
        chain: list[Node] = []
        host: Node | None = node
        while host is not None and host.id not in self._scales:
            if host.scale != UNIT_SCALE or host.is_motor:
                break
            chain.append(host)
            host = host.parent
        found: tuple[str, Pose] | None = None
        if host is not None and self._scales.get(host.id) == UNIT_SCALE:
            offset: Pose = (math3d.ORIGIN, math3d.IDENTITY)
            for link in reversed(chain):
                offset = math3d.compose(offset, link.local_pose())
            found = (host.id, offset)
        self._offsets[node.id] = found
        return found
