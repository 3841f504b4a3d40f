"""Where Bullet put each part, and where the nodes that parts carry are.

A sensor on a fingertip is not a body: its pose is its part's pose in Bullet composed
with the sensor's offset from the part (one or two local poses), for all watched sensors
at once in numpy, by the same operations as :func:`server.core.kit.math3d.compose`. A
node under a stretched part or a motor is posed by its tree instead
(:meth:`~server.core.model.node.Node.world_pose`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from ..kit import math3d
from ..kit.math3d import Pose, Vec3
from ..model.node import UNIT_SCALE, Node

PoseArrays = Callable[[Sequence[str]], "tuple[np.ndarray, np.ndarray]"]  # positions, quaternions
CARRIED_SETS = 64  # sets of nodes whose carriers are kept (watched sensors: one set)


@dataclass(frozen=True)
class _Carried:
    """Nodes (by index in a list of them) that parts carry: the part carrying each and the
    node's offset from it; and the nodes posed by their tree instead (``own``)."""

    own: list[int]
    rows: np.ndarray
    hosts: list[str]
    positions: np.ndarray
    quats: np.ndarray


class PartPoses:
    """The parts' poses as Bullet last gave them, and what the parts carry."""

    def __init__(self) -> None:
        self._poses: dict[str, Pose] = {}
        self._scales: dict[str, Vec3] = {}  # each part's world scale
        # node id -> the part carrying it and its offset from it (None: none); until a build
        self._offsets: dict[str, tuple[str, Pose] | None] = {}
        self._carried: dict[tuple[str, ...], _Carried] = {}  # node ids -> as world_poses needs

    def placed(self, keys: Sequence[str], poses: Sequence[Pose],
               scales: Sequence[Vec3] | None = None) -> None:
        """Parts are at these poses now (with these world scales, when built again)."""
        self._poses.update(zip(keys, poses))
        if scales is not None:
            self._scales.update(zip(keys, scales))

    def forget(self, keys: Sequence[str]) -> None:
        """Parts without a body any more: nothing is carried by them."""
        if keys:
            self.forget_offsets()
        for key in keys:
            self._poses.pop(key, None)

    def forget_offsets(self) -> None:
        """Trees were built again: offsets are worked out anew."""
        self._offsets.clear()
        self._carried.clear()

    def world_poses(self, nodes: list[Node], part_poses: PoseArrays) -> tuple[np.ndarray, np.ndarray]:
        """World positions (n×3) and quaternions (n×4) of nodes: the pose in Bullet of the
        unscaled part that carries a node (``part_poses`` gives them as arrays, for parts
        by id), composed with the node's offset from it, for all such nodes at once; else
        the tree's own (:meth:`Node.world_pose`)."""
        key = tuple(node.id for node in nodes)
        carried = self._carried.get(key)
        if carried is None:
            if len(self._carried) >= CARRIED_SETS:
                self._carried.clear()
            carried = self._carried[key] = self._carriers(nodes)
        positions, quats = np.empty((len(nodes), 3)), np.empty((len(nodes), 4))
        for index in carried.own:
            positions[index], quats[index] = nodes[index].world_pose()
        if carried.hosts:
            positions[carried.rows], quats[carried.rows] = math3d.compose_arrays(
                *part_poses(carried.hosts), carried.positions, carried.quats)
        return positions, quats

    def _carriers(self, nodes: list[Node]) -> _Carried:
        """Which of ``nodes`` their parts carry, and their offsets, as arrays."""
        found = [self._offset(node) for node in nodes]
        rows = [index for index, host in enumerate(found) if host is not None]
        offsets = [found[index][1] for index in rows]  # type: ignore[index]
        return _Carried(own=[index for index, host in enumerate(found) if host is None],
                        rows=np.array(rows, dtype=np.int64),
                        hosts=[found[index][0] for index in rows],  # type: ignore[index]
                        positions=np.array([p for p, _ in offsets]).reshape(-1, 3),
                        quats=np.array([q for _, q in offsets]).reshape(-1, 4))

    def _offset(self, node: Node) -> tuple[str, Pose] | None:
        """The unscaled part that carries ``node`` and the node's pose relative to it; None
        when the tree's own pose must be used. Kept until a tree is built again (every
        change of a pose below a root, or of a parent, rebuilds its tree)."""
        if node.id in self._offsets:
            return self._offsets[node.id]
        chain: list[Node] = []
        host: Node | None = node
        while host is not None and host.id not in self._poses:
            if host.scale != UNIT_SCALE or host.is_motor:
                break
            chain.append(host)
            host = host.parent
        found: tuple[str, Pose] | None = None
        if host is not None and host.id in self._poses and self._scales[host.id] == UNIT_SCALE:
            offset: Pose = (math3d.ORIGIN, math3d.IDENTITY)
            for link in reversed(chain):
                offset = math3d.compose(offset, link.local_pose())
            found = (host.id, offset)
        self._offsets[node.id] = found
        return found
