"""Who may change what: every object belongs to the client that made it.

An object's owner is the part of its id before the first dot (``c7`` of ``c7.3/1``;
``demo`` for the server's own). A controller changes only what it owns, with one door
open: a robot its owner shared (``share()``; the demo's robots are) may be steered by
anyone (the methods the API table marks ``steer``: motor angles) and others may attach
their own parts to it (``attach``, and parameters marked ``destination``). Reading,
sensing and watching stay open to all. Refusals name the owner.

A scene has a keeper: the controller that made it (the first to join; when it has gone
for good, the longest-connected controller left, or the next to join), or the server for
a scene its own setup makes (the demo). What changes the whole scene for everyone who
watches it (the methods marked ``keeper``: its physics) is the keeper's, or a controller's
that presented the server's control token: a stranger on the demo cannot make it
unwatchable.
"""

from __future__ import annotations

from typing import Any, Iterator, Sequence

from ..kit.errors import Forbidden
from ..kit.ids import owner_of
from ..model.node import Node
from ..model.robot import Robot
from .api import Method, Param
from .arguments import NODE_KINDS


def shared_robot(node: Node) -> Robot | None:
    """The robot ``node`` belongs to, if its owner shared it."""
    root = node.root()
    return root if isinstance(root, Robot) and root.shared else None


SERVER_KEEPER = "the server"  # the keeper of a scene the server's own setup makes


class Ownership:
    """The checks for one client (its id is the owner part of what it makes; ``trusted``:
    it presented the server's control token)."""

    def __init__(self, client_id: str, trusted: bool = False) -> None:
        self.client_id = client_id
        self.trusted = trusted

    def owns(self, node: Node) -> bool:
        """True when the client made ``node``."""
        return owner_of(node.id) == self.client_id

    def check_delete(self, node: Node) -> None:
        """Only the owner deletes."""
        if not self.owns(node):
            raise _refusal(node, "only its owner deletes it")

    def check_call(self, target: Node | None, method: Method, values: Sequence[Any],
                   keeper: str | None = None) -> None:
        """A changing call on ``target`` (None: the scene, kept by ``keeper``) with bound
        arguments ``values``."""
        if target is None and method.access == "keeper" and not self.trusted and \
                keeper is not None and keeper != self.client_id:
            raise Forbidden(f"this scene is {keeper}'s: only it, or a controller with the "
                            f"server's control token (vp-server --token, connect with token=), "
                            f"may {method.name}; a scene of your own (?scene=NAME) is yours",
                            keeper=keeper)
        if target is not None and not self.owns(target):
            self._check_foreign_target(target, method)
        for node, destination in _nodes_named(method.params, values):
            if self.owns(node) or (destination and shared_robot(node) is not None):
                continue
            raise _refusal(node, "only its owner attaches or moves it" if not destination else
                           f"attaching to it needs {owner_of(node.id)} to share its robot "
                           f"(share())")

    def _check_foreign_target(self, target: Node, method: Method) -> None:
        robot = shared_robot(target)
        if robot is None:
            raise _refusal(target, f"only its owner may {method.name}")
        if method.access == "owner":
            raise _refusal(target, f"its robot {robot.id} is shared, which lets others set "
                                   f"motor angles and attach their own parts, not {method.name}")


def _refusal(node: Node, why: str) -> Forbidden:
    owner = owner_of(node.id)
    return Forbidden(f"{node.id} belongs to {owner}: {why}", object=node.id, owner=owner)


def _nodes_named(params: Sequence[Param], values: Sequence[Any]) -> Iterator[tuple[Node, bool]]:
    """Every node in bound arguments, with whether it is an attach destination."""
    for index, param in enumerate(params):
        if param.kind not in NODE_KINDS:
            continue
        if param.variadic:
            for k, value in enumerate(values[index:]):
                for node in _nodes_in(value):
                    yield node, param.destination and k == 0
            return
        if index < len(values):
            for node in _nodes_in(values[index]):
                yield node, param.destination


def _nodes_in(value: Any) -> Iterator[Node]:
    if isinstance(value, Node):
        yield value
    elif isinstance(value, (list, tuple)):
        for item in value:
            yield from _nodes_in(item)
