"""``saveState`` / ``restoreState`` / ``forgetState`` (not in the manual): a scene's state
kept in its process and put back, as a learning environment resets an episode.

A state is the scene as its document holds it (:mod:`.scene_document`: every object, its
place, its motors' angles and targets, masses, frictions, the physics) and which sensors
are watched. Restoring puts the scene back as an import does, in a fresh physics world
built in the order the objects were made, every body at rest: the same steps after it give
the same world, bit for bit, however many times it is restored (a world that has been
running keeps its contact caches and the ids Bullet reused, and does not). Velocities are
not kept: a state saved while things move comes back at rest where they were.

Restoring replaces every object, so it is refused while the scene (now or in the state)
holds objects of other clients; and, as ``setPhysics``, it is the scene's keeper's. Every
client gets a fresh snapshot after it. A scene keeps at most ``savedStates`` states
(a limit: ``vp-server --limit savedStates=N``); ``forgetState`` frees one.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..kit.errors import Forbidden, LimitExceeded, UnknownObject
from ..kit.ids import owner_of
from ..scene.scene import Scene
from .scene_document import export_scene, import_scene


@dataclass(frozen=True)
class SavedState:
    """What :func:`save_state` keeps: the scene's document and its watched sensors."""

    document: dict[str, Any]
    watches: dict[str, list[str]]


def save_state(scene: Scene) -> str:
    """Keep the scene's state now; its id, for :func:`restore_state`."""
    kept = scene.saved_states
    if len(kept) >= scene.limits.saved_states:
        raise LimitExceeded(f"scene {scene.name} keeps at most {scene.limits.saved_states} saved "
                            f"states; forgetState frees one", limit="savedStates",
                            value=scene.limits.saved_states)
    scene.states_saved += 1
    state_id = f"state-{scene.states_saved}"
    kept[state_id] = SavedState(export_scene(scene, embed_assets=False), scene.watches.holders())
    return state_id


def restore_state(scene: Scene, state: str, client: str) -> None:
    """Put the scene back as it was when ``state`` was saved (see the module)."""
    saved = _saved(scene, state)
    owners = {owner_of(node_id) for node_id in scene.nodes} | \
        {owner_of(entry["id"]) for entry in saved.document["nodes"]}
    others = sorted(owners - {client})
    if others:
        raise Forbidden(f"restoring {state} would replace objects of {', '.join(others[:5])}: a "
                        f"scene is restored only when every object in it is the caller's",
                        clients=", ".join(others[:5]))
    with scene.journal.transaction():
        import_scene(scene, saved.document)
    for sensor, watchers in saved.watches.items():
        if sensor in scene.nodes:
            for watcher in watchers:
                scene.watches.add(sensor, watcher)
    scene.restart_feed()
    scene.restored = True


def forget_state(scene: Scene, state: str) -> None:
    """Free a saved state."""
    _saved(scene, state)
    del scene.saved_states[state]


def _saved(scene: Scene, state: str) -> SavedState:
    saved = scene.saved_states.get(state)
    if saved is None:
        kept = ", ".join(scene.saved_states) or "none"
        raise UnknownObject(f"no saved state {state!r} in scene {scene.name} (kept: {kept})",
                            object=state)
    return saved  # type: ignore[no-any-return]


# The scene's methods this module answers (operations.py calls them for the scene)
SCENE_CALLS = {"saveState": lambda scene, client: save_state(scene),
               "restoreState": lambda scene, state, client: restore_state(scene, state, client),
               "forgetState": lambda scene, state, client: forget_state(scene, state)}
