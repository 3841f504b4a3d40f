"""The physical side of a scene: bodies and ray shapes of its parts, contacts and sensing.

Every physical part in the scene has a collision body (:mod:`server.core.physics.engine`) and a
ray shape (:mod:`server.core.physics.raycast`) at its world pose. The scene marks what changed;
:meth:`SceneBodies.sync` brings the bodies in step before anything is measured, moving all
the parts that only moved in one batch (their world poses, one PyBullet call each, their
boxes in one array operation). The scene's tree stays the one source of poses: PyBullet
never moves anything by itself (kinematic mode, as 1.0).
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING, Callable, Iterable, Mapping

from ..kit.limits import Limits
from ..model.node import UNIT_SCALE, Node
from ..model.readings import Reading, read_sensors
from ..physics.assets import AssetLibrary
from ..physics.contacts import ContactBook, ContactTracker, Overlaps
from ..physics.engine import PhysicsWorld
from ..physics.geometry import scaled
from ..physics.raycast import RayTargets

if TYPE_CHECKING:
    from ..kit.math3d import Pose, Vec3

log = logging.getLogger(__name__)


class SceneBodies:
    """Collision bodies and ray shapes of the physical parts of one scene's nodes.

    Only parts that are :meth:`~server.core.model.node.Node.in_scene` have bodies (a robot
    taken out of the scene keeps its parts, without bodies).
    """

    def __init__(self, nodes: Mapping[str, Node], limits: Limits, assets: AssetLibrary, name: str = "") -> None:
        self._nodes = nodes
        self._name = name
        self.physics = PhysicsWorld()
        self.rays = RayTargets(assets)
        self.tracker = ContactTracker(self.physics, limits.contact_tests, limits.contact_pairs)
        self.contacts = ContactBook()  # as announced by the last tick
        self._dirty: set[str] = set()
        self._scales: dict[str, Vec3] = {}  # world scales of bodies not at 1, 1, 1
        self.failures = 0  # parts that could not be placed (a bug; logged)

    def close(self) -> None:
        """Release the physics world."""
        self.physics.close()

    def __len__(self) -> int:
        return len(self.physics)

    def mark(self, node_ids: Iterable[str]) -> None:
        """These nodes were made, moved, deleted or shown: their bodies follow at the next sync."""
        self._dirty.update(node_ids)

    # --- keeping bodies in step ------------------------------------------------------------

    def sync(self) -> None:
        """Create, move or remove the bodies and ray shapes of every marked part."""
        if not self._dirty:
            return
        moved: list[Node] = []
        for node_id in self._dirty:
            self._guarded(node_id, lambda i: self._place(i, moved))
        self._dirty.clear()
        if moved:
            try:
                self._move([node.id for node in moved], [node.world_pose() for node in moved])
            except Exception:  # a bug: place them one by one, leaving out the failing ones
                for node in moved:
                    self._guarded(node.id, self._sync_body)
        if self.physics.needs_rebuild():
            self.physics.rebuild()

    def _place(self, node_id: str, moved: list[Node]) -> None:
        """Note a part that only moved (placed in one batch), or make or remove its body."""
        node = self._nodes.get(node_id)
        if node is not None and node_id in self.physics and self._only_moved(node):
            moved.append(node)
        else:
            self._sync_body(node_id)

    def _only_moved(self, node: Node) -> bool:
        """True when the part keeps its body and shape and only its pose may differ."""
        return node.physical and node.in_scene() and \
            self._scales.get(node.id, UNIT_SCALE) == node.world_scale()

    def _move(self, keys: list[str], poses: list[Pose]) -> None:
        self.physics.move_many(keys, poses)
        self.rays.move_many(keys, poses)
        self.tracker.placed(keys)

    def _guarded(self, node_id: str, work: Callable[[str], None]) -> None:
        try:
            work(node_id)
        except Exception:  # a bug: this part is left out, the scene goes on
            self.failures += 1
            log.exception("part %s of scene %s could not be placed", node_id, self._name)
            self._forget(node_id)

    def _sync_body(self, node_id: str) -> None:
        """Make the part's body and shape afresh (or only remove them when it is gone)."""
        self._forget(node_id)
        node = self._nodes.get(node_id)
        if node is None or not node.physical or not node.in_scene():
            return
        geometry, pose, scale = node.geometry(), node.world_pose(), node.world_scale()
        if scale != UNIT_SCALE:
            geometry = scaled(geometry, scale)
            self._scales[node_id] = scale
        self.rays.add(node_id, geometry, pose)
        self.physics.add(node_id, geometry, pose)
        self.tracker.placed([node_id])

    def _forget(self, node_id: str) -> None:
        self._scales.pop(node_id, None)
        if node_id in self.physics:
            self.physics.remove(node_id)
            self.tracker.removed(node_id)
        if node_id in self.rays:
            self.rays.remove(node_id)

    # --- contacts and sensors --------------------------------------------------------------

    def overlaps(self) -> Overlaps:
        """The pairs touching now, as far as one update's budget of tests measures."""
        self.sync()
        self.tracker.update()
        return self.tracker.overlaps()

    def touching(self, part: Node | None, exact: bool = True) -> list[str]:
        """Ids of what ``part`` touches, sorted ("ground" for the ground).

        Exact: measured now. Otherwise as of the last tick (watched readings use that).
        """
        if part is None:
            return []
        if exact:
            self.sync()
            self.tracker.settle(part.id)
        return list(self.tracker.overlaps().of(part.id))

    def read(self, sensors: list[Node], exact: bool = True) -> dict[str, Reading]:
        """Readings of ``sensors`` for the scene as it is now."""
        self.sync()
        return read_sensors(self.rays, sensors,
                            lambda sensor: self.touching(sensor.host(), exact))
