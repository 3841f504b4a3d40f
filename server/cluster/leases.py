"""Which worker runs which scene: a key per scene in the bus's ``vp_leases`` bucket, whose
value is the worker's name. The bucket forgets a key ``seconds`` after it was last written,
so a worker renews its leases while it lives; when it dies they lapse and another worker
may claim them (sooner when it is seen to have left the bus: :func:`break_lease`). Claims and renewals are compare-and-set on the key's revision: two
workers never both hold a scene."""

from __future__ import annotations

import logging

from nats.js.errors import KeyDeletedError, KeyNotFoundError, KeyWrongLastSequenceError
from nats.js.kv import KeyValue

log = logging.getLogger(__name__)


async def lease_holder(leases: KeyValue, scene: str) -> str | None:
    """The worker that holds ``scene``'s lease, if one does."""
    try:
        entry = await leases.get(scene)
    except (KeyNotFoundError, KeyDeletedError):
        return None
    return entry.value.decode() if entry.value else None


async def break_lease(leases: KeyValue, scene: str, worker: str) -> None:
    """Delete ``scene``'s lease if ``worker`` still holds it: the worker has left the bus
    (nobody listens on its subjects), so its scenes need not wait for the lease to lapse."""
    try:
        entry = await leases.get(scene)
    except (KeyNotFoundError, KeyDeletedError):
        return
    if entry.value and entry.value.decode() == worker:
        try:
            await leases.delete(scene, last=entry.revision)
            log.warning("scene %s: the lease of worker %s, which has left the bus, is broken",
                        scene, worker)
        except (KeyWrongLastSequenceError, KeyNotFoundError):
            pass  # renewed or taken meanwhile: not broken


class Leases:
    """The leases one worker holds."""

    def __init__(self, leases: KeyValue, worker: str) -> None:
        self._leases = leases
        self.worker = worker
        self._revisions: dict[str, int] = {}  # scene -> the revision this worker wrote

    def __contains__(self, scene: str) -> bool:
        return scene in self._revisions

    async def claim(self, scene: str) -> str | None:
        """Take the scene's lease unless another worker holds it: that worker's name, or
        None when this worker holds it now."""
        if scene in self._revisions:
            return None
        try:
            self._revisions[scene] = await self._leases.create(scene, self.worker.encode())
            return None
        except KeyWrongLastSequenceError:
            holder = await lease_holder(self._leases, scene)
            if holder is None:  # it lapsed between the two calls
                return await self.claim(scene)
            if holder == self.worker:  # ours from before a restart of this worker's host
                return await self._retake(scene)
            return holder

    async def _retake(self, scene: str) -> str | None:
        entry = await self._leases.get(scene)
        try:
            self._revisions[scene] = await self._leases.update(scene, self.worker.encode(),
                                                               last=entry.revision)
        except KeyWrongLastSequenceError:
            return await lease_holder(self._leases, scene)
        return None

    async def renew(self) -> list[str]:
        """Write every lease again; the scenes whose lease was lost meanwhile (it lapsed and
        another worker took it): this worker must stop running them."""
        lost = []
        for scene, revision in list(self._revisions.items()):
            try:
                self._revisions[scene] = await self._leases.update(
                    scene, self.worker.encode(), last=revision)
            except (KeyWrongLastSequenceError, KeyNotFoundError):
                self._revisions.pop(scene, None)
                if await self.claim(scene) is not None:
                    log.error("worker %s lost the lease of scene %s", self.worker, scene)
                    lost.append(scene)
        return lost

    async def release(self, scene: str) -> None:
        """Give the scene's lease up (its process has ended)."""
        revision = self._revisions.pop(scene, None)
        if revision is None:
            return
        try:
            await self._leases.delete(scene, last=revision)
        except (KeyWrongLastSequenceError, KeyNotFoundError):
            pass  # lapsed already, or taken: not ours to delete
