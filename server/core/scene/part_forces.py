"""What presses on a scene's parts (dynamic mode), as Bullet's last step left it and as the
frames have told it: frames carry each part's force when it changes, to 1 mN, and a
snapshot gives a newcomer the forces told so far."""

from __future__ import annotations

from ..model.node import Node
from ..physics.bullet_parts import BulletParts


class PartForces:
    """Newtons pressing on each part (none in kinematic mode)."""

    def __init__(self, parts: BulletParts) -> None:
        self._parts = parts
        self._told: dict[str, float] = {}  # by the frames so far (changed)

    def changed(self) -> dict[str, float]:
        """Newtons on each part whose force changed since the last call (0: it ended),
        rounded to 1 mN, as frames carry them."""
        now = {key: round(force, 3) for key, force in self._parts.forces.items()}
        changed = {key: force for key, force in now.items() if self._told.get(key) != force}
        changed.update((key, 0.0) for key in self._told if key not in now)
        self._told = {key: force for key, force in now.items() if force}
        return changed

    def told(self) -> dict[str, float]:
        """Newtons on each pressed part as the frames sent so far have told them: what a
        snapshot gives a newcomer, so that a force that stopped changing is still known."""
        return dict(self._told)

    def peak(self) -> float:
        """The most newtons pressing on any one part at the last tick."""
        return max(self._parts.forces.values(), default=0.0)

    def on(self, part: Node | None) -> float:
        """Newtons pressing on ``part`` at the last tick."""
        return 0.0 if part is None else self._parts.forces.get(part.id, 0.0)
