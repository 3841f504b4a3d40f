"""Which worker runs which scene, in two of the bus's key-value buckets:

- ``vp_workers``: a key per living worker, which the bucket forgets ``seconds`` after it
  was last written; each worker writes its own again several times a lease, one write
  however many scenes it runs.
- ``vp_scenes``: a key per scene, naming the worker that runs it. It holds only while
  that worker's key lives: once the worker's key lapses (the worker died, or was cut off
  from the bus), another worker may take the scene over.

Claims and takeovers are compare-and-set on a key's revision: two workers never both take
a scene. A worker seen to have left the bus (nobody listens on its subjects) need not be
waited for: :func:`break_worker` deletes its key at once.
"""

from __future__ import annotations

import logging

from nats.js.errors import KeyDeletedError, KeyNotFoundError, KeyWrongLastSequenceError, NoKeysError
from nats.js.kv import KeyValue

log = logging.getLogger(__name__)


async def _value(bucket: KeyValue, key: str) -> tuple[str | None, int]:
    """A key's value and revision (None and 0 when it has none)."""
    try:
        entry = await bucket.get(key)
    except (KeyNotFoundError, KeyDeletedError):
        return None, 0
    return (entry.value.decode() if entry.value else None), entry.revision or 0


async def worker_lives(workers: KeyValue, worker: str) -> bool:
    """Whether ``worker``'s key is there (written within a lease)."""
    return (await _value(workers, worker))[0] is not None


async def living_workers(workers: KeyValue) -> set[str]:
    """The workers whose keys are there (each written within a lease)."""
    try:
        return set(await workers.keys())
    except NoKeysError:
        return set()


async def lease_holder(workers: KeyValue, scenes: KeyValue, scene: str) -> str | None:
    """The living worker that runs ``scene``, if one does."""
    holder, _ = await _value(scenes, scene)
    return holder if holder is not None and await worker_lives(workers, holder) else None


async def break_worker(workers: KeyValue, worker: str) -> None:
    """``worker`` has left the bus: its scenes may be taken over now, not a lease later."""
    value, revision = await _value(workers, worker)
    if value is None:
        return
    try:
        await workers.delete(worker, last=revision)
        log.warning("worker %s has left the bus: its scenes may start elsewhere", worker)
    except (KeyWrongLastSequenceError, KeyNotFoundError):
        pass  # written again meanwhile: it lives


class Leases:
    """One worker's key and the scenes it holds."""

    def __init__(self, workers: KeyValue, scenes: KeyValue, worker: str) -> None:
        self._workers, self._scenes = workers, scenes
        self.worker = worker
        self._held: set[str] = set()
        self._revision = 0  # of this worker's own key

    def __contains__(self, scene: str) -> bool:
        return scene in self._held

    async def start(self) -> None:
        """Write this worker's key: it lives."""
        self._revision = await self._workers.put(self.worker, b"alive")

    async def claim(self, scene: str) -> str | None:
        """Take the scene unless a living worker holds it: that worker's name, or None when
        this worker holds it now."""
        holder, revision = await _value(self._scenes, scene)
        if holder == self.worker or (holder is not None
                                     and not await worker_lives(self._workers, holder)) \
                or holder is None:
            try:
                if holder is None:
                    await self._scenes.create(scene, self.worker.encode())
                elif holder != self.worker:  # its worker is gone: taken over
                    await self._scenes.update(scene, self.worker.encode(), last=revision)
            except KeyWrongLastSequenceError:  # another worker was quicker
                return await lease_holder(self._workers, self._scenes, scene) or \
                    await self.claim(scene)
            self._held.add(scene)
            return None
        return holder

    async def renew(self) -> list[str]:
        """Write this worker's key again; the scenes it lost meanwhile (its key lapsed and
        another worker took them): this worker must stop running them."""
        try:
            self._revision = await self._workers.update(self.worker, b"alive",
                                                        last=self._revision)
            return []
        except (KeyWrongLastSequenceError, KeyNotFoundError):
            pass
        self._revision = await self._workers.put(self.worker, b"alive")  # it lapsed: back
        lost = []
        for scene in list(self._held):
            if (await _value(self._scenes, scene))[0] != self.worker:
                self._held.discard(scene)
                log.error("worker %s lost scene %s to another worker", self.worker, scene)
                lost.append(scene)
        return lost

    async def release(self, scene: str) -> None:
        """Give the scene up (its process has ended)."""
        if scene not in self._held:
            return
        self._held.discard(scene)
        holder, revision = await _value(self._scenes, scene)
        if holder == self.worker:
            try:
                await self._scenes.delete(scene, last=revision)
            except (KeyWrongLastSequenceError, KeyNotFoundError):
                pass  # taken meanwhile: not ours to delete
