"""The bus: one NATS connection (``nats-py``, NATS's own client), the subjects and
key-value buckets the cluster uses, and how its messages are packed.

Subjects (scene and worker names are plain: letters, digits, ``_`` and ``-``)::

    vp.place                        every worker answers how many scenes it runs and
                                    whether it has room (a gateway places a new scene on
                                    the least busy with room)
    vp.worker.<w>.attach            a gateway asks worker <w> to run a scene for it
    vp.worker.<w>.alive             a gateway's heartbeat; <w> answers which of its scenes
                                    it still runs
    vp.worker.<w>.scene.<s>         commands for scene <s> (from any gateway, in order)
    vp.gateway.<g>.alive            a worker asks whether gateway <g>, silent a while, lives
    vp.scene.<s>.events             everything scene <s> says: published once, received
                                    by every gateway attached to it, in the order it was said

Buckets: ``vp_workers`` and ``vp_scenes`` (which worker runs which scene:
:mod:`.leases`) and ``vp_cluster`` (the resume keys' secret, how far client ids have been
handed out: :mod:`.client_ids`).

Messages are the typed values of :mod:`.bus_messages` (and the scene's own commands and
events, :mod:`server.web.process.messages`), pickled as on the pipes between a server and
its scene processes: the bus is part of one deployment and must be
reachable by its processes only (NATS accounts or TLS when it leaves one machine).
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import pickle
import time
from typing import Any, Awaitable, Callable
from urllib.parse import urlsplit

import nats
from nats.aio.client import Client
from nats.aio.msg import Msg
from nats.errors import NoRespondersError, NoServersError, TimeoutError as RequestTimeout
from nats.js.errors import BadRequestError
from nats.js.kv import KeyValue

from ..core.kit.errors import BusUnavailable, TooLarge

log = logging.getLogger(__name__)
PLACE = "vp.place"  # gateways ask every worker how busy it is (a Load each)
LOADS = "vp.loads"  # a worker tells every gateway its Load when it changes
CONNECT_SECONDS = 60.0  # a process started with its bus waits this long for it
# a bus cut off without its connection closing (a partition) is noticed within about
# PING_SECONDS * (PINGS_OUT + 1), not nats-py's default of minutes
PING_SECONDS, PINGS_OUT = 2.0, 2
WORKERS, SCENES, CLUSTER = "vp_workers", "vp_scenes", "vp_cluster"
Handler = Callable[[Any, "ReturnAddress | None"], Awaitable[None] | None]


def attach_subject(worker: str) -> str:
    return f"vp.worker.{worker}.attach"


def alive_subject(worker: str) -> str:
    return f"vp.worker.{worker}.alive"


def gateway_subject(gateway: str) -> str:
    return f"vp.gateway.{gateway}.alive"


def gateway_of(attachment: str) -> str:
    """The gateway an attachment (``<gateway>-<number>``) belongs to."""
    return attachment.rpartition("-")[0]


def commands_subject(worker: str, scene: str) -> str:
    return f"vp.worker.{worker}.scene.{scene}"


def events_subject(scene: str) -> str:
    return f"vp.scene.{scene}.events"


class Unanswered(Exception):
    """A request nobody answered: no subscriber (``gone``: its worker is gone) or not in
    time (it may only be slow)."""

    def __init__(self, text: str, gone: bool) -> None:
        super().__init__(text)
        self.gone = gone


class ReturnAddress:
    """The way back to a request's sender."""

    def __init__(self, bus: Bus, subject: str) -> None:
        self._bus, self._subject = bus, subject

    async def send(self, value: Any) -> None:
        await self._bus.publish(self._subject, value)


class OrderedSender:
    """Publishes in the order things were sent, never waiting the sender: one queue and one
    task for everything a gateway or a worker says on the bus."""

    def __init__(self, bus: Bus) -> None:
        self._bus = bus
        self._queue: asyncio.Queue[tuple[str, Any]] = asyncio.Queue()

    def send(self, subject: str, value: Any) -> None:
        self._queue.put_nowait((subject, value))

    async def run(self) -> None:
        """Publish forever (a task of its owner's life)."""
        while True:
            subject, value = await self._queue.get()
            try:
                await self._bus.publish(subject, value)
            except Exception:  # too large, or the bus is away: that one is lost
                if self._bus.link.down_since is None:
                    log.exception("publishing on %s", subject)
                # (away: the client keeps what it can, pending_size, then refuses; the link
                # has said the bus is away, once: not a traceback a message)

    async def flush(self) -> None:
        """Publish what is still queued (its owner is stopping)."""
        while not self._queue.empty():
            await self._bus.publish(*self._queue.get_nowait())


class Link:
    """Whether the bus is reachable now, as the client's own callbacks say: it notices a
    bus that went away (its connection closed, or PINGS_OUT pings unanswered) and comes back
    by itself."""

    def __init__(self, url: str) -> None:
        self.where = shown_address(url)
        self.down_since: float | None = None  # (time.monotonic())
        self.up_since = time.monotonic()
        self.returned: list[Callable[[], None]] = []  # called whenever it is back
        self.closing = False  # this process leaves the bus: its going is no outage

    async def lost(self) -> None:
        if self.down_since is None and not self.closing:
            self.down_since = time.monotonic()
            log.error("the bus at %s is unreachable", self.where)

    async def back(self) -> None:
        if self.down_since is not None:
            log.warning("the bus at %s is back after %.1f s", self.where,
                        time.monotonic() - self.down_since)
        self.down_since, self.up_since = None, time.monotonic()
        for call in self.returned:
            call()

    @property
    def down_for(self) -> float:
        """Seconds since the bus went away (0 while it is reachable)."""
        return 0.0 if self.down_since is None else time.monotonic() - self.down_since

    def refusal(self, what: str) -> BusUnavailable:
        """The error of a request that needs the bus while it is away."""
        return BusUnavailable(f"{what}: the cluster's bus at {self.where} has been unreachable "
                              f"for {self.down_for:.0f} s; try again once it is back",
                              bus=self.where)

    def check(self, what: str) -> None:
        """Raise :meth:`refusal` while the bus is away."""
        if self.down_since is not None:
            raise self.refusal(what)

    def problems(self) -> list[str]:
        """What ``/api/health`` says of the bus."""
        if self.down_since is None:
            return []
        return [f"the cluster's bus at {self.where} has been unreachable for "
                f"{self.down_for:.0f} s: scenes run by workers cannot be reached"]


def shown_address(url: str) -> str:
    """The bus's address without any user or password in it."""
    parts = urlsplit(url)
    return f"{parts.scheme}://{parts.hostname}" + (f":{parts.port}" if parts.port else "")


class Bus:
    """A connection to the bus, with the cluster's buckets."""

    def __init__(self, client: Client, workers: KeyValue, scenes: KeyValue,
                 shared: KeyValue, lease_seconds: float, link: Link) -> None:
        self.client = client
        self.link = link
        self.workers = workers  # the living workers, expiring (server.cluster.leases)
        self.lease_seconds = lease_seconds  # how long a worker's key lives: the bucket's
        self.scenes = scenes  # scene -> the worker running it
        self.shared = shared  # cluster-wide facts (server.cluster.client_ids)

    @classmethod
    async def connect(cls, url: str, name: str, lease_seconds: float) -> Bus:
        """Connect (retrying while the bus starts), making the buckets if they are missing."""
        deadline = asyncio.get_running_loop().time() + CONNECT_SECONDS
        link = Link(url)
        while True:
            try:
                client = await nats.connect(url, name=name, connect_timeout=2,
                                            max_reconnect_attempts=-1, reconnect_time_wait=0.5,
                                            ping_interval=PING_SECONDS,
                                            max_outstanding_pings=PINGS_OUT,
                                            error_cb=_bus_trouble, disconnected_cb=link.lost,
                                            reconnected_cb=link.back)
                break
            except (NoServersError, OSError) as error:
                if asyncio.get_running_loop().time() > deadline:
                    raise ConnectionError(f"the bus at {url} does not answer") from error
                log.warning("waiting for the bus at %s", url)
                await asyncio.sleep(1.0)
        stream = client.jetstream()
        try:
            workers = await stream.create_key_value(bucket=WORKERS, ttl=lease_seconds, history=1)
        except BadRequestError:  # made by a process with another --lease-seconds: that one holds
            workers = await stream.key_value(WORKERS)
        ttl = (await workers.status()).ttl or lease_seconds
        scenes = await stream.create_key_value(bucket=SCENES, history=1)
        shared = await stream.create_key_value(bucket=CLUSTER, history=1)
        return cls(client, workers, scenes, shared, ttl, link)

    def pack(self, value: Any) -> bytes:
        data = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        if len(data) > self.client.max_payload:
            raise TooLarge(f"{len(data)} bytes is more than the bus carries in one message "
                           f"({self.client.max_payload} bytes: nats-server's max_payload)",
                           limit="max_payload", value=self.client.max_payload)
        return data

    async def publish(self, subject: str, value: Any) -> None:
        await self.client.publish(subject, self.pack(value))

    async def request(self, subject: str, value: Any, timeout: float) -> Any:
        """Ask and wait for the answer; :class:`Unanswered` when none comes."""
        try:
            message = await self.client.request(subject, self.pack(value), timeout=timeout)
        except NoRespondersError:
            raise Unanswered(f"{subject}: nobody listens", gone=True) from None
        except RequestTimeout:
            raise Unanswered(f"{subject}: no answer within {timeout} s", gone=False) from None
        return pickle.loads(message.data)

    async def gather(self, subject: str, value: Any, wait: float,
                     enough: Callable[[list[Any]], bool] | None = None) -> list[Any]:
        """Ask everyone listening on ``subject``; the answers that came within ``wait``
        seconds, or as soon as ``enough(answers)`` says they are all there."""
        answers: list[Any] = []
        complete = asyncio.Event()

        async def collect(message: Msg) -> None:
            if message.data:  # (not the bus's own "no responders")
                answers.append(pickle.loads(message.data))
                if enough is not None and enough(answers):
                    complete.set()
        inbox = self.client.new_inbox()
        subscription = await self.client.subscribe(inbox, cb=collect)
        try:
            await self.client.publish(subject, self.pack(value), reply=inbox)
            with contextlib.suppress(asyncio.TimeoutError):
                await asyncio.wait_for(complete.wait(), wait)
        finally:
            await subscription.unsubscribe()
        return answers

    async def subscribe(self, subject: str, handler: Handler) -> Any:
        """Call ``handler(value, reply)`` for each message, in order; the subscription."""
        async def receive(message: Msg) -> None:
            reply = ReturnAddress(self, message.reply) if message.reply else None
            try:
                outcome = handler(pickle.loads(message.data), reply)
                if outcome is not None:
                    await outcome
            except Exception:  # one bad message must not end the subscription
                log.exception("handling a message on %s", subject)
        return await self.client.subscribe(subject, cb=receive)

    async def close(self) -> None:
        self.link.closing = True
        try:
            await self.client.drain()
        except Exception:  # already closed, or the bus is gone: nothing left to drain
            await self.client.close()


async def _bus_trouble(error: Exception) -> None:
    """The client's own errors (the bus went away, a reconnection failed): one line each,
    not a traceback; it reconnects by itself."""
    log.warning("bus: %s", error or type(error).__name__)
