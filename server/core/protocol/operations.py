"""Applying protocol operations (create, call, delete, batch) to a scene via the API table."""

from __future__ import annotations

from typing import Any, Callable

from ..kit.errors import BadMessage, LimitExceeded, UnknownMethod, UnknownType, VPError
from ..kit.numbers import encode_numbers
from ..model.node import Node
from ..scene.scene import Scene
from . import api
from .arguments import bind
from .node_classes import NODE_CLASSES
from .ownership import Ownership
from .saved_states import SCENE_CALLS

SCENE_ID = "scene"


def _ref(node: Node | None) -> dict[str, str] | None:
    return None if node is None else {"ref": node.id}


RESULTS: dict[str, Callable[[Any, Any], Any]] = {
    "none": lambda target, value: None,
    "self": lambda target, value: _ref(target),
    "ref": lambda target, value: _ref(value),
    "refs": lambda target, value: [_ref(v) for v in value],
    "ids": lambda target, value: [{"ref": v} for v in value],
    "bool": lambda target, value: bool(value),
    "number": lambda target, value: encode_numbers(float(value)),
    "numbers": lambda target, value: encode_numbers([float(v) for v in value]),
    "point": lambda target, value: list(value),
    "physics": lambda target, value: value,  # already its wire form (Physics.wire)
    "contacts": lambda target, value: value,  # already its wire form (ContactForce.wire)
    "gripMap": lambda target, value: value,  # already its wire form (GripMap.wire)
    "name": lambda target, value: value,  # a string, or None
    "string": lambda target, value: str(value),
    "recording": lambda target, value: value,  # what a recording holds (mcap_recorder)
}


class Operations:
    """Turns checked protocol messages into calls on a scene and results into wire values."""

    def __init__(self, scene: Scene, client_id: str, trusted: bool = False) -> None:
        self.scene = scene
        self.client_id = client_id
        self.ownership = Ownership(client_id, trusted)
        self.keep = False  # what this client makes stays when it leaves (Node.keep)

    def type_of(self, object_id: str) -> str:
        """The API type name of an object (``Scene`` for the scene itself)."""
        return "Scene" if object_id == SCENE_ID else self.scene.get(object_id).type_name

    def method(self, object_id: str, name: str) -> api.Method:
        """The table entry of a method of an object, or :class:`UnknownMethod`."""
        type_name = self.type_of(object_id)
        method = api.methods_of(type_name).get(name)
        if method is None:
            raise UnknownMethod(f"{type_name} has no method {name!r}", object=object_id,
                                method=name)
        return method

    def mutates(self, op: dict[str, Any]) -> bool:
        """True when the operation would change the scene (viewers may not send those)."""
        if op["op"] == "call":
            return self.method(op["object"], op["method"]).mutates
        return op["op"] != "ping"

    def apply(self, op: dict[str, Any]) -> Any:
        """Apply one checked operation inside the caller's transaction; its wire result."""
        kind = op["op"]
        if kind == "create":
            return self.create(op["object"], op["type"], op.get("args", []))
        if kind == "call":
            return self.call(op["object"], op["method"], op.get("args", []))
        if kind == "delete":
            node = self.scene.get(op["object"])
            self.ownership.check_delete(node)
            self.scene.delete(node)
            return None
        if kind == "batch":
            limit = self.scene.limits.batch_ops
            if len(op["ops"]) > limit:
                raise LimitExceeded(f"{len(op['ops'])} operations in one batch; at most {limit}",
                                    limit="batchOps", value=limit)
            return self._apply_batch(op["ops"])
        if kind == "ping":
            return {"time": self.scene.time, "seq": self.scene.seq}
        raise BadMessage(f"op {kind!r} cannot be applied")

    def _apply_batch(self, ops: list[dict[str, Any]]) -> list[Any]:
        """A batch's operations in order, in one try (an animation step's twenty calls);
        an error names the operation that failed."""
        results: list[Any] = []
        call, apply = self.call, self.apply
        try:
            for op in ops:
                results.append(call(op["object"], op["method"], op.get("args", []))
                               if op["op"] == "call" else apply(op))
        except VPError as error:
            index = len(results)
            error.message = f"batch op {index} ({ops[index]['op']}): {error.message}"
            error.args = (error.message,)
            error.details["index"] = index
            raise
        return results

    def create(self, object_id: str, type_name: str, raw_args: list[Any]) -> dict[str, str]:
        """Make a new object of a manual type with the manual's constructor arguments."""
        spec = api.TYPES.get(type_name)
        if spec is None or not spec.creatable:
            creatable = sorted(name for name, t in api.TYPES.items() if t.creatable)
            raise UnknownType(f"unknown type {type_name!r}; the types are {', '.join(creatable)}",
                              type=type_name)
        args = bind(spec.params, raw_args, self.scene.get, f"new {type_name}")
        node = NODE_CLASSES[type_name](self.scene, object_id, *args)
        if self.keep:
            node.keep()
        return {"ref": node.id}

    def call(self, object_id: str, name: str, raw_args: list[Any]) -> Any:
        """Call a manual method on an object (or on the scene) and convert its result."""
        method = self.method(object_id, name)
        target = self.scene if object_id == SCENE_ID else self.scene.get(object_id)
        args = bind(method.params, raw_args, self.scene.get, f"{name} of {object_id}")
        if method.mutates:
            self.ownership.check_call(None if target is self.scene else target, method, args,
                                      self.scene.keeper)
        extra = {"client": self.client_id} if method.client else {}
        if target is self.scene and name in SCENE_CALLS:
            value = SCENE_CALLS[name](self.scene, *args, client=self.client_id)
        else:
            value = getattr(target, method.python)(*args, **extra)
        return RESULTS[method.returns](target, value)
