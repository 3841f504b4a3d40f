"""One scene in a process of its own: its sessions, requests, ticks, reads and encoding.

PyBullet holds the GIL for every call it makes, so scenes on threads of one process take
turns: a flooded scene once delayed every other scene's frames by up to a second. Here
each scene owns a process (and a core when it needs one); the event loop's process only
moves text. This module is the process's side: :func:`serve` runs until told to stop or
until the pipe to the server closes. No asyncio here.

Commands come from the server in lists and events go back in lists: the messages and
what each causes are in :mod:`.messages`.
"""

from __future__ import annotations

import logging
import os
import signal
import sys
import time
from collections import deque
from pathlib import Path
from multiprocessing.connection import Connection as Pipe
from typing import Any

from ...core.kit.limits import Limits
from ...core.kit.math3d import Quat, Vec3
from ...core.kit.numbers import encode_numbers
from ...core.kit.wire_messages import WarningMessage
from ...core.physics.assets import AssetLibrary
from ...core.protocol.messages import encode
from ...core.protocol.robot_files import place_robot
from ...core.protocol.scene_document import check_import, import_scene, parse_document, scene_owners
from ...core.protocol.session import Session
from .parent_death import end_with_parent
from ...core.scene.scene import Scene
from ...core.kit.errors import InternalError, UnknownRecording, VPError
from . import heap
from ..connections.outgoing import Outgoing
from ..recording.recording_file import SceneRecordings
from .messages import (Admit, Answers, Ask, Command, ConnectionId, Event, Frame, Idle, Import,
                       Join, Leave, Metrics, Place, Question, Read, Ready, Record, Recorded,
                       RecordingStarted, Reply, Saving, Stop, Text, Unrecord)
from .saving import SceneSaver
from .scene_metrics import SceneMetrics
from .scene_start import SERVER_OWNER, Animator, SceneSetup, start_scene
from ..storage.scene_store import SceneStore
from ..storage.upload_folder import UploadFolder

log = logging.getLogger(__name__)
FLUSH_EVENTS = 256  # events sent in one go at most, so answers flow during long floods
SAVE_FAILED = 75  # exit code of a scene's process that stopped with changes it could not save


def serve(pipe: Pipe, name: str, limits: Limits, tick_rate: float, assets: AssetLibrary,
          setup: SceneSetup | None, log_level: int, store: SceneStore | None = None,
          recordings: Path | None = None, nice: int = 0) -> None:
    """The process's main function: make the scene (as ``setup`` makes it, then as its
    saved document says, when there is one), then serve it (``nice``: this much below the
    server's own priority)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the server stops its scenes itself
    _end_with_the_server()
    if nice:
        os.nice(nice)
    logging.basicConfig(level=log_level)
    scene = Scene(name, limits, assets, UploadFolder(assets))
    worker = SceneWorker(pipe, scene, tick_rate, store, recordings)
    worker.prepare(setup)
    worker.ready()
    heap.settle()
    try:
        worker.run()
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_IGN)  # stopping already: let it finish
        if worker.recordings.current is not None:
            worker.recordings.end("the scene stopped")
        worker.flush()  # the server hears of it, and of answers held for a frame
        durable = worker.saver.close()  # the server stopped it, or the server is gone
        scene.close()
    if not durable:
        sys.exit(SAVE_FAILED)


def _end_with_the_server() -> None:
    """Stop (as the server would stop it: recording closed, document saved) once the
    server's process has gone, kill -9 included: the pipe's end tells the loop so between
    ticks, the parent-death signal also during one long call into PyBullet."""
    signal.signal(signal.SIGTERM, _stop_now)
    end_with_parent(signal.SIGTERM)


def _stop_now(signum: int, frame: Any) -> None:
    raise SystemExit(0)


class SceneWorker:
    """The loop of a scene's process: commands in arrival order, a tick whenever due."""

    def __init__(self, pipe: Pipe, scene: Scene, tick_rate: float,
                 store: SceneStore | None = None, recordings: Path | None = None) -> None:
        self.scene = scene
        self.tick_rate = tick_rate
        self.metrics = SceneMetrics()
        self._pipe = pipe
        self._animator: Animator | None = None  # the setup's (prepare)
        self._sessions: dict[int, Session] = {}
        self._commands: deque[Command] = deque()
        self._events: list[Event] = []
        self._later = 0  # how many of _events may wait for the next frame (the rest: not)
        self._resync = False
        self._stopping = False
        self._departed: dict[str, tuple[float, Session]] = {}  # client -> (deadline, session)
        self._left: set[str] = set()  # of those, the clients that were connected here
        self._store = store
        self._notices: list[Outgoing] = []  # warnings for every client, sent with the next tick
        self.recordings = SceneRecordings(
            scene, recordings, lambda recording: self._events.append(RecordingStarted(recording)),
            lambda summary: self._events.append(Recorded(summary)))
        scene.recorder = self.recordings  # a client's startRecording and stopRecording
        self.saver = SceneSaver(scene, store, self._tell,
                                lambda report: self._events.append(Saving(report)))

    def run(self) -> None:
        """Serve until ``stop`` or until the server's end of the pipe closes."""
        period = 1.0 / self.tick_rate
        last = deadline = time.monotonic()
        while not self._stopping:
            if self.idle():  # nobody to tell and nothing to do: wait for a command
                self._events.append(Idle())  # the server knows this silence is sleep
                self._flush()
                if not self._receive(None):
                    return
                if not self._commands:  # only figures asked for (answered): sleep on
                    self._flush()
                    continue
                deadline = time.monotonic()  # and tick at once: the clock catches up
                continue
            now = time.monotonic()
            if now >= deadline:
                if self.scene.clock.paused:
                    self._stand()
                else:
                    self._tick(now - last)
                last, deadline = now, max(deadline + period, now - 5 * period)
                # a scene whose ticks run late still hears its server (and its going)
                # and still serves requests, half a period's worth after every tick
                if not self._receive(0):
                    return
                self._serve(time.monotonic() + period / 2)
            elif self._commands:
                self._serve(deadline)
            elif not self._receive(deadline - now):
                return

    def idle(self) -> bool:
        """True when a tick would have nothing to do or tell: no client connected or within
        its grace period, no animation, nothing changed, queued, unsaved or (dynamic mode)
        still moving. The scene then stops ticking; its next tick (before any command is
        served) advances its clock by the whole time it waited, so the time it reads is right."""
        saver = self.saver
        return not (self._sessions or self._departed or self._commands or self._notices
                    or self._resync or self._events or self._animator is not None
                    or self.scene.feed.pending or self.scene.moving
                    or saver.saved is False or saver.at_risk)

    def _serve(self, until: float) -> None:
        """Apply queued commands until ``until`` (at least one), then send what they made,
        unless all of it may go with the next tick's frame (:func:`_with_the_frame`)."""
        while self._commands:
            self._command(self._commands.popleft())
            if len(self._events) >= FLUSH_EVENTS:
                self._flush()
            if time.monotonic() >= until:
                break
        if len(self._events) > self._later:
            self._flush()

    def _receive(self, wait: float | None) -> bool:
        """Wait up to ``wait`` seconds (None: until one comes) for commands, then take every one sent so far;
        False once the server is gone. ``metrics`` is answered at once, ahead of a backlog
        of requests: a scene working through one is when its figures matter most."""
        try:
            ready = self._pipe.poll(wait)
            while ready:
                for command in self._pipe.recv():
                    if isinstance(command, Ask) and isinstance(command.question, Metrics):
                        self._command(command)
                    else:
                        self._commands.append(command)
                ready = self._pipe.poll(0)
        except (EOFError, OSError):
            return False
        return True

    def flush(self) -> None:
        """Send the events made so far."""
        self._flush()

    def _flush(self) -> None:
        self.saver.commit()  # changes are on the disk before their answers leave
        self._later = 0
        if self._events:
            events, self._events = self._events, []
            try:
                self._pipe.send(events)
            except (BrokenPipeError, OSError):
                self._stopping = True

    def _command(self, command: Command) -> None:
        try:
            match command:
                case Text(cid, text):
                    self._text(cid, text)
                case Join():
                    self._join(command)
                case Leave(cid):
                    self._leave(cid)
                case Ask(number, question):
                    self._events.append(self._reply(number, question))
                case Stop():
                    self._stopping = True
                case _:
                    raise TypeError(f"not a command of a scene's process: {command!r}")
        except Exception:  # a bug in one command must not stop the scene
            log.exception("command %s of scene %s failed", type(command).__name__, self.scene.name)

    def _join(self, join: Join) -> None:
        client_id = join.client_id
        self._departed.pop(client_id, None)  # back within the grace period: nothing goes
        self._left.discard(client_id)
        session = self._sessions[join.cid] = Session(self.scene, client_id, join.role,
                                                     resume=join.resume, trusted=join.trusted)
        if join.role == "controller" and self.scene.keeper is None:
            self.scene.keeper = client_id
        session.operations.keep = join.keep
        session.on_change = self.saver.changed
        session.on_step = self._take_steps
        self._events.append(Admit(join.cid, [Outgoing.of(session.hello(self.tick_rate)),
                                             Outgoing.of(self.scene.snapshot())]))

    def _text(self, cid: ConnectionId, text: str | bytes) -> None:
        session = self._sessions.get(cid)
        now = time.monotonic()
        if session is not None:
            self.recordings.request(session.client_id, text)
        answered = [] if session is None else session.receive_encoded(text, now)
        answers = [Outgoing(answer["op"], encoded) for answer, encoded in answered]
        self.metrics.served(now, len(answers))
        self._take_steps()  # a step's ticks, before its answer
        self._events.append(Answers(cid, answers, len(text)))
        if not self.scene.clock.paused and all(map(_with_the_frame, answered)):
            self._later += 1  # (a paused scene's next frame waits for a step: never held)

    def _take_steps(self) -> None:
        """The ticks steps asked for, taken now (their frames go before the answers); after
        a restoreState, everyone's snapshot first (a step in the same text ticks after it)."""
        if self.scene.restored:
            self.scene.restored = False
            self._resync = True
            self._stand()
            self.saver.save(replaced=True)
        for _ in range(self.scene.clock.take()):
            self._tick(1.0 / self.tick_rate, send=False)  # with the answer: one send

    def _leave(self, cid: ConnectionId) -> None:
        session = self._sessions.pop(cid, None)
        if session is None or \
                any(s.client_id == session.client_id for s in self._sessions.values()):
            return  # the client is back already (a new connection took over)
        self._depart(session)
        self._left.add(session.client_id)

    def _depart(self, session: Session) -> None:
        """What the client made and did not keep goes when its grace period is over."""
        grace = self.scene.limits.leave_grace_seconds
        self._departed[session.client_id] = (time.monotonic() + grace, session)

    def _expire(self, now: float) -> None:
        """Delete what clients that left made, once their grace period is over."""
        for client_id, (deadline, session) in list(self._departed.items()):
            if now >= deadline:
                del self._departed[client_id]
                self._left.discard(client_id)
                if self.scene.keeper == client_id:  # gone for good: the longest-connected
                    self.scene.keeper = next((s.client_id for s in self._sessions.values()
                                              if s.role == "controller"), None)
                deleted = session.close()
                self.saver.left(client_id)
                if deleted:
                    heap.trim()  # what the client's objects used goes back to the system

    def _reply(self, number: int, question: Question) -> Reply:
        """The answer to a question, or the error that refused it."""
        try:
            return Reply(number, True, self._answer(question))
        except VPError as error:
            return Reply(number, False, error)
        except Exception:
            asked = question.function.__name__ if isinstance(question, Read) else \
                type(question).__name__
            log.exception("question %s to scene %s failed", asked, self.scene.name)
            return Reply(number, False, InternalError("internal server error"))

    def _answer(self, question: Question) -> Any:
        match question:
            case Read(function, args):
                result = function(self.scene, *args)
                return result if isinstance(result, bytes) else encode(encode_numbers(result))
            case Import(body, replace):
                return encode(encode_numbers(self._import(body, replace)))
            case Place(file, position, quaternion):
                return encode(encode_numbers(self._place(file, position, quaternion)))
            case Metrics():
                summary = self.metrics.summary(time.monotonic(), time.process_time())
                return {**summary, **self.saver.report()}
            case Record(recording_id, path):
                self.recordings.begin(recording_id, Path(path))
                return {"id": recording_id, "scene": self.scene.name, "sceneTime": self.scene.time}
            case Unrecord(recording_id):
                return self._unrecord(recording_id)
        raise TypeError(f"not a question for a scene's process: {question!r}")

    def _import(self, body: bytes, replace: bool) -> dict[str, Any]:
        """Replace the scene by a document's bytes, unless it would take what a client here
        owns (:func:`check_import`)."""
        scene = self.scene
        document = parse_document(body)
        check_import(scene, document, self._present(), replace)
        with scene.journal.transaction():
            summary = import_scene(scene, document)
        self._restarted(summary["owners"])
        self._tell("replaced", f"scene {scene.name} was replaced by an import "
                               f"({summary['objects']} objects)")
        self.saver.save(replaced=True)
        return {**summary, "owners": scene_owners(scene)}  # the ids it used too

    def _place(self, file: str, position: Vec3, quaternion: Quat) -> dict[str, Any]:
        """A robot from an uploaded robot file, saved at once."""
        with self.scene.journal.transaction():
            report = place_robot(self.scene, file, position, quaternion)
        self.saver.save(replaced=True)
        return report

    def _present(self) -> set[str]:
        """Clients connected to the scene, or that were and are within their grace period."""
        return {s.client_id for s in self._sessions.values()} | self._left

    def _tell(self, code: str, message: str) -> None:
        """A warning for every client of the scene, sent with the next tick."""
        self._notices.append(Outgoing.of(WarningMessage(op="warning", code=code, message=message)))

    def ready(self) -> None:
        """Tell the server the scene is made, with every owner of its objects and ids: no
        newcomer may be given one of those ids."""
        self._events.append(Ready(scene_owners(self.scene)))
        self._flush()

    def prepare(self, setup: SceneSetup | None) -> None:
        """Make the scene as its store last saved it and as ``setup`` says
        (:func:`.scene_start.start_scene`); the owners of its objects may each come back in
        their grace period (nobody is connected yet)."""
        self._animator, owners = start_scene(self.scene, self._store, self.saver, setup)
        for owner in owners:
            self._depart(Session(self.scene, owner))

    def _restarted(self, owners: list[str]) -> None:
        """After the whole scene was replaced: a fresh snapshot for everyone, and owners
        who are not here get a grace period to come back, as if they had just left."""
        self.scene.restart_feed()
        self._resync = True
        here = {session.client_id for session in self._sessions.values()}
        for owner in owners:
            if owner not in here and owner != SERVER_OWNER:
                self._depart(Session(self.scene, owner))

    def _unrecord(self, recording_id: str) -> dict[str, Any]:
        current = self.recordings.current
        if current is None or current.id != recording_id:
            raise UnknownRecording(f"scene {self.scene.name!r} is not recording {recording_id!r}",
                                   recording=recording_id)
        return self.recordings.end("stopped")

    def _tick(self, dt: float | None, send: bool = True) -> None:
        """Run the animator, advance the scene (None: a paused scene's stand) and send its
        messages to every client (``send`` False: with the next events sent, as a step's
        frames go with its answer)."""
        started = time.perf_counter()
        try:
            if self._animator is not None and dt is not None:
                self._animator(self.scene, self.scene.time + dt)
            ticked = self.scene.stand() if dt is None else self.scene.tick(dt)
            messages = self._notices + self._resynced() + [Outgoing.of(m) for m in ticked]
            self._notices = []
            self.recordings.tick(ticked)
        except Exception:  # the scene kept what it had not sent; clients resync later
            self.metrics.tick_failures += 1
            self._resync = True
            log.exception("tick of scene %s failed", self.scene.name)
            if send:  # answers held for this tick's frame go without it
                self._flush()
            return
        self._expire(time.monotonic())  # deleted now, announced by the next tick
        if messages:
            self._events.append(Frame(messages))
        if send:
            self._flush()
        self.saver.tick(time.monotonic())
        self.metrics.ticked(time.monotonic(), (time.perf_counter() - started) * 1000,
                            time.process_time(), self.scene.bodies.forces.peak())

    def _stand(self) -> None:
        """A due tick of a paused scene: its clock stands, but what requests changed still
        reaches every client (a frame of no time), and clients that left still go."""
        if self.scene.feed.pending or self._notices or self._resync:
            self._tick(None)
        else:
            self._expire(time.monotonic())
            self.saver.tick(time.monotonic())
            if self._events:  # (answers held for a frame that this stand does not make)
                self._flush()

    def _resynced(self) -> list[Outgoing]:
        """After a failed tick, a fresh snapshot first: every client rebuilds from it."""
        if not self._resync:
            return []
        self._resync = False
        return [Outgoing.of(self.scene.snapshot())]


def _with_the_frame(answered: tuple[dict[str, Any], str]) -> bool:
    """Whether an answer may wait for the next tick's frame, to leave with it: an ``ok`` to
    a batch of setters (every result null), such as an animation step's. Sent at once,
    it cost a message from the scene's process and a wake-up of the server's a step (a
    script animating ten hands: 9 % of the scene's process went to writing its pipe); it
    comes at most a tick later, just before that frame. Anything else (a read's result, an
    error, a single call, any answer in a paused scene) leaves at once."""
    answer, _ = answered
    results = answer.get("result")
    return answer["op"] == "ok" and type(results) is list and bool(results) and \
        all(result is None for result in results)
