"""The server's handle on one scene's process (:mod:`server.web.process.worker`).

The event loop writes commands to the process's pipe and reads its events as they come
(:mod:`.process_pipe`), so it never blocks on a pipe: a scene busy with a flood fills its
own pipe and slows only its own clients. A thread starts the process (a fork server's
reply, a predecessor's end to wait for) and one waits for its end. Processes start from a
fork server that has already imported the scene code, so a new scene is ready in
milliseconds.
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import logging
import multiprocessing
import os
import socket
import threading
import time
from multiprocessing import spawn
from pathlib import Path
from typing import Any, Callable, Protocol

from ...core.kit.limits import Limits
from ...core.physics.assets import AssetLibrary
from ...core.kit.errors import UnknownScene, VPError
from ..process import fork_server, forkserver_main, worker
from ..process.scene_start import SceneSetup
from ..process.messages import Ask, Command, Ended, Event, Question, Reply, Stop
from ..storage.scene_store import SceneStore
from .process_pipe import ProcessPipe

log = logging.getLogger(__name__)
Deliver = Callable[[list[Event]], None]
COMMANDS_PER_SEND = 512  # commands pickled together: fewer, larger writes in a flood
PREDECESSOR_SECONDS = 30.0  # how long a scene waits for its stopping predecessor's last save

CONTEXT = multiprocessing.get_context("forkserver")
# scipy's hulls too: a dynamic scene's first hand measures its parts' volumes with them.
# Not trimesh (meshes, imports, exports): a third of a CPU-second of every server's start,
# paid instead by the first scene that reads a mesh; nor scipy.optimize (0.1 CPU-s of every
# start, for the rare cut envelope whose corners miss its cuts). Nor the server's script
# (forkserver_main.py: its processes are told they already run it).
PRELOAD = [forkserver_main.__name__, worker.__name__, "scipy.spatial",
           "server.web.process.forkserver_heap"]  # last: freezes what they loaded
CONTEXT.set_forkserver_preload(PRELOAD)


def start_fork_server() -> bool:
    """Start the fork server now, as a fork of this process (:mod:`..process.fork_server`:
    its modules are imported already); False when only multiprocessing's own can start
    (threads running), which it does when the first scene needs it."""
    return fork_server.fork_here(PRELOAD)


def _tell_the_fork_server_the_script() -> None:
    """Where the fork server's processes find their script (forkserver_main.py), before it
    starts. Each process says its own (a server started by a test or the bench inherits
    theirs); one still starting, importing this to unpickle what it runs, may not ask
    multiprocessing, and keeps its parent's."""
    with contextlib.suppress(RuntimeError):  # (multiprocessing: "bootstrapping phase")
        os.environ[forkserver_main.MAIN_PATH] = spawn.get_preparation_data("scene").get(
            "init_main_from_path", "")  # (a module run with -m: imported by name, not run)


_tell_the_fork_server_the_script()


class Replies:
    """The answered commands a runner has sent (``call``), by number, until their replies
    come or the scene ends: one for a scene's process here and for one on a worker."""

    def __init__(self) -> None:
        self._waiting: dict[int, asyncio.Future[Any]] = {}
        self._numbers = itertools.count(1)

    def ask(self, post: Callable[[Command], None], question: Question,
            refusal: Exception | None = None) -> asyncio.Future[Any]:
        """``post(Ask(number, question))``; the reply, awaitable (``refusal`` at once, if
        given: the scene has ended)."""
        future = asyncio.get_running_loop().create_future()
        if refusal is not None:
            future.set_exception(refusal)
            return future
        number = next(self._numbers)
        self._waiting[number] = future
        post(Ask(number, question))
        return future

    def answer(self, reply: Reply) -> None:
        future = self._waiting.pop(reply.number, None)
        if future is None or future.done():
            return
        if reply.ok:
            future.set_result(reply.value)
        else:
            future.set_exception(reply.value)

    def fail(self, scene: str, why: VPError | None = None) -> None:
        """The scene has ended: every reply still awaited is ``why`` (by default
        ``unknown_scene``)."""
        for future in self._waiting.values():
            if not future.done():
                future.set_exception(why or UnknownScene(f"scene {scene} has ended", scene=scene))
        self._waiting.clear()


class Runner(Protocol):
    """A scene's process as the event loop drives it: :class:`SceneRunner` here, or a
    cluster's worker over the bus (:mod:`server.cluster.remote_runner`)."""

    name: str
    tick_rate: float
    last_posted: float
    ended: bool
    stopping: bool
    expecting: bool  # a client waits for the scene (a cluster counts it as attended)

    @property
    def pid(self) -> int | None: ...

    @property
    def unsaved(self) -> bool: ...

    def start(self, after: Runner | None = None) -> None: ...

    def post(self, command: Command) -> None: ...

    def call(self, question: Question) -> asyncio.Future[Any]: ...

    def stop(self) -> None: ...

    def join(self, timeout: float) -> None: ...


# name, limits, tick rate, assets, setup, deliver, store, recordings' folder
RunnerFactory = Callable[[str, Limits, float, AssetLibrary, "SceneSetup | None", Deliver,
                          "SceneStore | None", "Path | None"], Runner]


class SceneRunner:
    """Starts a scene's process, sends it commands, and hands its events to ``deliver``
    on the event loop (a final :class:`Ended` when the process is gone; a cluster's runner
    may say why the scene never started: its ``refusal``)."""

    expecting = False  # (a cluster's runner tells its worker; here nothing counts it)

    def __init__(self, name: str, limits: Limits, tick_rate: float, assets: AssetLibrary,
                 setup: SceneSetup | None, deliver: Deliver,
                 store: SceneStore | None = None, recordings: Path | None = None,
                 nice: int = 0) -> None:
        self.name = name
        self.tick_rate = tick_rate
        self._deliver = deliver
        self._loop = asyncio.get_running_loop()
        self._pipe, child = CONTEXT.Pipe()
        self._process = CONTEXT.Process(
            target=worker.serve, name=f"scene-{name}", daemon=True,
            args=(child, name, limits, tick_rate, assets, setup, logging.getLogger().level, store,
                  recordings, nice))
        self._child = child
        self._commands: list[Command] = []  # posted, to be written at the loop's turn
        self._link: ProcessPipe | None = None  # the pipe, once the process has started
        self._written_stop = False  # nothing is written after Stop
        self._attaching: asyncio.Task[None] | None = None
        self._replies = Replies()
        self.last_posted = 0.0  # when the last command was sent (monotonic)
        self.ended = False
        self.stopping = False  # asked to stop: however the process ends, it is no failure
        self._started = threading.Event()
        # Only the reaper waits on the process (_reap): two threads waiting at once both read the
        # fork server's one report of its end, and one of them gets 255 for it.
        self._gone = threading.Event()
        self.exitcode: int | None = None  # once the process has ended

    @property
    def pid(self) -> int | None:
        return self._process.pid

    def start(self, after: Runner | None = None) -> None:
        """Start the process (in a thread: it waits for the fork server), then read and
        write its pipe on the loop; with ``after`` (the scene's process still stopping),
        once that has ended: its last save is what this one restores. Commands posted
        meanwhile wait."""
        threading.Thread(target=self._launch, args=(after,), name=f"to-{self.name}",
                         daemon=True).start()

    def _launch(self, after: Runner | None) -> None:
        if after is not None:
            after.join(PREDECESSOR_SECONDS)
        try:
            self._process.start()
        except Exception:  # out of processes or memory: the scene ends as a failed one
            log.exception("the process of scene %s did not start", self.name)
            self._gone.set()
            self._hand_over(self._end, 1)
            return
        finally:
            self._started.set()
            self._child.close()  # the child's end lives in the child now: EOF when it dies
        self._hand_over(self._attach, None)

    def _attach(self, _: None) -> None:
        self._attaching = self._loop.create_task(self._attached())

    async def _attached(self) -> None:
        """Read and write the pipe on the loop from now on (its socket, taken from the
        multiprocessing connection), and write what was posted meanwhile."""
        link = ProcessPipe(self._receive, self._lost)
        try:
            pipe = socket.socket(fileno=os.dup(self._pipe.fileno()))
        except OSError:  # (ended meanwhile, or no descriptor left: it ends as a failed one)
            self._lost()
            return
        self._pipe.close()
        try:
            await self._loop.connect_accepted_socket(lambda: link, pipe)
        except OSError:
            pipe.close()
            self._lost()
            return
        self._link = link
        self._write()

    def post(self, command: Command) -> None:
        """Send a command; the scene applies commands in the order they were posted (those
        posted in one turn of the loop go together)."""
        self.last_posted = time.monotonic()
        if not self._commands:
            self._loop.call_soon(self._write)
        self._commands.append(command)

    def call(self, question: Question) -> asyncio.Future[Any]:
        """Ask the scene (``Read``, ``Metrics``, …); its reply, awaitable."""
        return self._replies.ask(self.post, question, UnknownScene(
            f"scene {self.name} was removed", scene=self.name) if self.ended else None)

    def stop(self) -> None:
        """Ask the process to finish the commands sent so far, then end."""
        self.stopping = True
        self.post(Stop())

    def kill(self) -> None:
        """End the process at once, unsaved: another process owns the scene now."""
        self.stopping = True
        self._started.wait()
        if self._process.pid is not None:
            self._process.kill()

    def join(self, timeout: float) -> None:
        """Wait for the process to end (killed after ``timeout`` seconds)."""
        self._started.wait(timeout)
        if self._process.pid is None:
            return  # never started
        if not self._gone.wait(timeout):
            self._process.kill()
            self._gone.wait(5)

    def _write(self) -> None:
        """Write the commands posted so far, unless the pipe is not open yet (they wait)
        or a Stop went (nothing follows it)."""
        if self._link is None or not self._commands:
            return
        commands, self._commands = self._commands, []
        if self._written_stop:
            return
        if any(isinstance(command, Stop) for command in commands):
            self._written_stop = True
            commands = commands[:next(k for k, c in enumerate(commands) if isinstance(c, Stop)) + 1]
        for first in range(0, len(commands), COMMANDS_PER_SEND):
            self._link.send(commands[first:first + COMMANDS_PER_SEND])

    def _lost(self) -> None:
        """The pipe closed: the process is ending (or hung on the way); its end is waited
        for in a thread, and reported on the loop."""
        threading.Thread(target=self._reap, name=f"end-{self.name}", daemon=True).start()

    def _reap(self) -> None:
        self._process.join(5)
        if self._process.exitcode is None:
            self._process.kill()
            self._process.join()
        self.exitcode = self._process.exitcode
        self._gone.set()
        self._hand_over(self._end, self.exitcode)

    def _hand_over(self, function: Callable[[Any], None], argument: Any) -> None:
        try:
            self._loop.call_soon_threadsafe(function, argument)
        except RuntimeError:  # the loop closed while the server stopped
            pass

    def _receive(self, events: list[Event]) -> None:
        rest = []
        for event in events:
            if isinstance(event, Reply):
                self._replies.answer(event)
            else:
                rest.append(event)
        if rest:
            self._deliver(rest)

    @property
    def unsaved(self) -> bool:
        """Whether the process ended with changes it could not save."""
        return self.exitcode == worker.SAVE_FAILED

    def _end(self, exitcode: int | None) -> None:
        self.ended = True
        self._pipe.close()
        if self._link is not None and self._link.transport is not None:
            self._link.transport.close()
        failed = bool(exitcode) and not self.stopping
        if failed:
            log.error("the process of scene %s ended with exit code %s", self.name, exitcode)
        self._replies.fail(self.name)
        self._deliver([Ended(failed)])
