"""A session: one connection to one scene of a server, with its mirror and its objects
(the JavaScript client's ``Session``)."""

from __future__ import annotations

import os
import threading
from contextlib import contextmanager
from itertools import count
from typing import Any, Callable, Iterator, Protocol, TypeVar
from urllib.parse import urlencode

from .codec import encode_arg
from .connection import Connection
from .errors import ConnectionLost, ServerError, Timeout, VPError
from .mirror import Mirror
from .viewer_cell import ViewerCell, viewer_url
from .waiting import bound, wait_seconds
from .wire_messages import Batch, Call, Create, Delete

T = TypeVar("T")
SCENE_ID = "scene"
_current: Session | None = None


class SceneObject(Protocol):
    """What the session needs of an object of this client (objects.py defines them)."""

    id: str


class ObjectClass(Protocol):
    """A class of objects (objects.py): it makes one for an id this client did not make."""

    def stand_in(self, session: Session, node_id: str) -> SceneObject: ...


# The class of every type, by type name: filled by runtime.py, which holds the table, so
# that this module needs none of the classes.
CLASSES: dict[str, ObjectClass] = {}


def current_session() -> Session:
    """The session new objects go to: the last one :func:`connect` opened."""
    if _current is None:
        raise VPError("not connected: call virtual_prosthetics.connect() first")
    return _current


def set_current_session(session: Session) -> None:
    """Make ``session`` the one new objects go to."""
    global _current
    _current = session


def trim(args: tuple[Any, ...]) -> list[Any]:
    """Arguments without trailing Nones (left-out arguments take the server's defaults)."""
    items = list(args)
    while items and items[-1] is None:
        items.pop()
    return [encode_arg(a) for a in items]


class Session:
    """One scene on a server, seen and driven through a WebSocket.

    Writes are sent at once and return; reads come from the mirror after every earlier
    write of this client has been answered, so a read always sees this client's writes.
    ``timeout``: the seconds to wait for the scene's snapshot and for every answer waited
    on (default: ``VP_TIMEOUT``, else 60; :mod:`.waiting`).
    """

    def __init__(self, url: str = "ws://127.0.0.1:8000", scene: str = "default",
                 role: str = "controller", timeout: float | None = None,
                 token: str | None = None, keep: bool = False) -> None:
        timeout = wait_seconds(timeout)
        self.url = url.rstrip("/")
        self.mirror = Mirror(self._listens)
        self.lock = threading.RLock()
        self.objects: dict[str, SceneObject] = {}
        self.hello: dict[str, Any] = {}
        self.animation: tuple[Callable[..., None], float] | None = None
        self._ids = count(1)
        self.holding = False  # this client paused the scene: its time is the frames' (run steps it)
        self._ready = threading.Event()
        token = token if token is not None else os.environ.get("VP_TOKEN")
        self.token = token  # uploads send it too
        query = urlencode({"scene": scene, "role": role, **({"token": token} if token else {}),
                           **({"keep": "true"} if keep else {})})
        self.connection = Connection(f"{url.rstrip('/')}/ws?{query}", self._on_message,
                                     self._on_changes, timeout)
        self.connection.start()
        if not self._ready.wait(bound(timeout)):
            self.connection.close()
            raise Timeout(f"no snapshot of scene {scene!r} from {self.url}", timeout)
        if "client" not in self.hello:
            self.connection.raise_deferred()
            raise ConnectionLost(self.connection.closed or "the server refused the connection")

    @property
    def name(self) -> str:
        """The scene's name."""
        return self.hello["scene"]

    @property
    def client_id(self) -> str:
        """This client's id (the prefix of every id it makes)."""
        return self.hello["client"]

    def _on_message(self, message: dict[str, Any]) -> None:
        if message["op"] == "hello":
            self.hello = message
            return
        with self.lock:
            self.mirror.apply(message)
        if message["op"] == "snapshot" or (message["op"] == "error" and not self.hello):
            self._ready.set()

    def _on_changes(self, changes: dict[str, Any]) -> None:
        with self.lock:
            self.mirror.apply_changes(changes)

    # --- requests ------------------------------------------------------------------------

    def new_id(self) -> str:
        """A fresh object id of this client."""
        return f"{self.client_id}.{next(self._ids)}"

    def create(self, obj: SceneObject, type_name: str, args: tuple[Any, ...]) -> None:
        """Ask the server to make ``obj`` (returns at once)."""
        self.objects[obj.id] = obj
        self.connection.send(Create(op="create", object=obj.id, type=type_name, args=trim(args)))

    def call(self, object_id: str, method: str, args: tuple[Any, ...] = (),
             wait: bool = False) -> Any:
        """Call a manual method on the server; with ``wait``, return its result."""
        return self.connection.send(Call(op="call", object=object_id, method=method,
                                         args=[encode_arg(a) for a in args]), wait=wait)

    def delete(self, object_id: str) -> None:
        """Delete an object and everything attached below it."""
        self.objects.pop(object_id, None)
        self.connection.send(Delete(op="delete", object=object_id))

    def read(self, reader: Callable[[Mirror], T]) -> T:
        """Run ``reader`` on the mirror once every earlier write has been answered."""
        self.connection.settle()
        with self.lock:
            return reader(self.mirror)

    def sync(self) -> None:
        """Wait until the server has answered everything sent; raise its first error.

        Contact callbacks due so far run here too.
        """
        self.connection.settle()
        self.dispatch_contacts()

    def proxy(self, node_id: str) -> SceneObject:
        """The object for an id: the one this client made, or a new stand-in of its type."""
        obj = self.objects.get(node_id)
        if obj is None:
            with self.lock:
                type_name = self.mirror.nodes[node_id]["type"]
            made = CLASSES.get(type_name) or CLASSES["Node"]
            obj = self.objects[node_id] = made.stand_in(self, node_id)
        return obj

    def resolve(self, node_id: str) -> SceneObject | str:
        """What an id in a reading or contact stands for in this client.

        The object this client made (or a part of it, such as a hand's finger); for
        objects other clients made, and for "ground", the id itself.
        """
        obj = self.objects.get(node_id)
        if obj is not None:
            return obj
        with self.lock:
            known = node_id in self.mirror.nodes
        if known and node_id.startswith(f"{self.client_id}."):
            return self.proxy(node_id)
        return node_id

    def _listens(self, node_id: str) -> bool:
        """Whether this client's object ``node_id`` overrides a contact callback."""
        return getattr(self.objects.get(node_id), "hears_contacts", False)

    def dispatch_contacts(self) -> None:
        """Call ``begin_contact``/``end_contact`` of this client's parts for every contact
        change received so far, in the order the server reported them.

        :func:`~virtual_prosthetics.run` calls this before every animation step and
        :meth:`sync` after waiting; a script without an animation loop may call it itself.
        """
        while True:
            with self.lock:
                if not self.mirror.events:
                    return
                kind, a, b = self.mirror.events.popleft()
            for this, other in ((a, b), (b, a)):
                callback = getattr(self.objects.get(this), f"{kind}_contact", None)
                if callback is not None:
                    callback(self.resolve(other))

    # --- the manual's scene functions ----------------------------------------------------

    def set_camera_position(self, *position: Any) -> None:
        """Manual ``setCameraPosition``: move every viewer's camera."""
        self.call(SCENE_ID, "setCameraPosition", position)

    def set_camera_target(self, *target: Any) -> None:
        """Manual ``setCameraTarget``: turn every viewer's camera."""
        self.call(SCENE_ID, "setCameraTarget", target)

    def set_caption(self, text: str) -> None:
        """Show ``text`` in a corner of every viewer of the scene (a task's name, trial, time
        and score; at most 200 characters, lines split at ``\\n``); "" hides it (not in the
        manual)."""
        self.call(SCENE_ID, "setCaption", (text,))

    def set_transforms(self, transforms: dict[Any, list[float]]) -> None:
        """Place many objects in one request: ``{obj: [px, py, pz, qx, qy, qz, qw]}``, with
        ``sx, sy, sz`` after to scale too (not in the manual)."""
        self.call(SCENE_ID, "setTransforms",
                  ({getattr(key, "id", key): list(value) for key, value in transforms.items()},))

    def set_physics(self, mode: str, **options: float) -> None:
        """``setPhysics`` (not in the manual): ``"kinematic"`` (1.0's: motors jump, nothing
        falls) or ``"dynamic"``, with options ``unit`` (metres per scene unit: masses,
        forces and torques are SI at the size it makes things), ``gravity``, ``substeps``,
        ``solver_iterations``, ``solver_tolerance``, ``friction``, ``density``,
        ``warm_start`` (left out: the defaults)."""
        wire = {_camel(name): value for name, value in options.items()}
        self.call(SCENE_ID, "setPhysics", (mode, wire) if wire else (mode,))

    def get_physics(self) -> dict[str, Any]:
        """The scene's physics: ``{"mode", "gravity", "substeps", …}`` (wire names), once
        every earlier write has been answered (a ``set_physics`` just sent included)."""
        return self.read(lambda mirror: dict(mirror.physics))

    def get_time(self) -> float:
        """Manual ``getTime()``: the server's scene time now (a scene this client paused:
        the time of the last tick it stepped to)."""
        self.connection.raise_deferred()
        with self.lock:
            return self.mirror.time if self.holding else self.mirror.now()

    @property
    def tick_rate(self) -> float:
        """The scene's ticks a second (a ``step`` of one tick is ``1 / tick_rate`` s)."""
        return float(self.hello["tickRate"])

    def pause(self) -> None:
        """Stop the scene's clock (not in the manual): nothing moves until :meth:`step`,
        whatever the server's load, until :meth:`resume` or until this client leaves."""
        self.call(SCENE_ID, "pause")
        self.connection.settle()
        self.holding = True

    def resume(self) -> None:
        """Let the scene's clock run with the wall clock again."""
        self.call(SCENE_ID, "resume")
        self.connection.settle()
        self.holding = False

    @contextmanager
    def paused(self) -> Iterator[None]:
        """The scene's clock held inside the block (:meth:`pause`, then :meth:`resume`;
        inside a block already paused, nothing more)."""
        if self.holding:
            yield
            return
        self.pause()
        try:
            yield
        finally:
            if self.connection.closed is None:
                self.resume()

    def step(self, ticks: int = 1) -> float:
        """Advance the paused scene by ``ticks`` ticks (1 to 60) with what was sent before
        (anything gathered leaves first); return once they are taken and their frames are
        in the mirror, with the scene's time. A ``not_paused`` answer ends :attr:`holding`
        (another client resumed, or a restarted server lost the pause)."""
        with self._stepping():
            self.call(SCENE_ID, "step", (ticks,))
            self.sync()
        with self.lock:
            return self.mirror.time

    @contextmanager
    def _stepping(self) -> Iterator[None]:
        """A ``not_paused`` answer inside ends :attr:`holding` (and is raised)."""
        try:
            yield
        except ServerError as error:
            if error.code == "not_paused":
                self.holding = False
            raise

    def step_reading(self, reads: list[tuple[str, str]], ticks: int = 1) -> list[Any]:
        """:meth:`step`, and the results of ``reads`` (``(object id, method)`` of reads
        without arguments: ``getSpeeds``, ``getTorques``…) as of after the ticks, in one
        message and one answer (the server takes a step's ticks before what follows it in a
        message): a learning environment's step."""
        with self._stepping():
            with self.connection.gathering():  # with what is gathered already, one text
                self.call(SCENE_ID, "step", (ticks,))
                return self.read_many(reads)

    def read_many(self, reads: list[tuple[str, str]]) -> list[Any]:
        """The results of ``reads`` (``(object id, method)`` of reads without arguments), in
        one message with whatever is gathered (:meth:`Connection.gathering`) and one answer;
        raises the first refusal of what was sent with them."""
        ops = [Call(op="call", object=target, method=method, args=[]) for target, method in reads]
        results = self.connection.send(Batch(op="batch", ops=ops), wait=True)
        self.connection.raise_deferred()
        self.dispatch_contacts()
        return list(results)

    def save_state(self) -> str:
        """``saveState`` (not in the manual): the server keeps the scene's state now (its
        objects, motors, masses, physics, watched sensors); its id, for :meth:`restore_state`."""
        return str(self.call(SCENE_ID, "saveState", wait=True))

    def restore_state(self, state: str, wait: bool = True) -> None:
        """``restoreState``: the scene put back as ``state`` was, every body at rest, in a
        fresh physics world (the same steps after it give the same world); returns once
        the mirror holds it (``wait=False``: at once; the answer to anything sent after it
        comes once the mirror holds it). Only the scene's keeper, and only while every
        object in it is this client's."""
        self.call(SCENE_ID, "restoreState", (state,), wait=wait)
        if wait:
            self.sync()

    def forget_state(self, state: str) -> None:
        """``forgetState``: the server frees a saved state."""
        self.call(SCENE_ID, "forgetState", (state,))

    def viewer_url(self, role: str = "viewer") -> str:
        """Where a browser watches this scene (``role="controller"``: with motor panels)."""
        return viewer_url(self.url, self.name, role, self.token)

    def show(self, width: int = 800, height: int = 500, role: str = "viewer") -> ViewerCell:
        """The live viewer of this scene, for a Jupyter cell: ``session.show()`` as a cell's
        last line draws it there (outside a notebook it prints the viewer's address)."""
        return ViewerCell(self.viewer_url(role), width, height)

    def close(self) -> None:
        """Disconnect; the server deletes what this client made."""
        global _current
        self.connection.close()
        if _current is self:
            _current = None

    def __enter__(self) -> Session:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def _camel(name: str) -> str:
    """``solver_iterations`` → ``solverIterations``."""
    head, *rest = name.split("_")
    return head + "".join(word.title() for word in rest)
