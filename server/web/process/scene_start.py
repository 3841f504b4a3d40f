"""How a scene's process makes its scene at start: as its store last saved it (the document,
then the changes journaled since), with the server's own objects as its setup makes them.

A setup (:data:`SceneSetup`) is the server's own content of a scene, such as the demo's
hands: it makes its objects under :data:`SERVER_OWNER` and may give an animator that runs
every tick. A saved document may hold the setup's objects already (in their last state):
those are kept, and the setup only gives its animator.
"""

from __future__ import annotations

import logging
from typing import Any, Callable

from ...core.kit.errors import VPError
from ...core.kit.ids import owner_of
from ...core.protocol.command_log import replay
from ...core.protocol.ownership import SERVER_KEEPER
from ...core.protocol.scene_document import import_scene
from ...core.scene.scene import Scene
from ..storage.scene_store import SceneStore
from .saving import SceneSaver

log = logging.getLogger(__name__)
Animator = Callable[[Scene, float], None]
SceneSetup = Callable[[Scene], Animator | None]
SERVER_OWNER = "demo"  # what the server's own setups make: never anyone's to leave


def start_scene(scene: Scene, store: SceneStore | None, saver: SceneSaver,
                setup: SceneSetup | None) -> tuple[Animator | None, list[str]]:
    """Make ``scene`` as ``store`` last saved it, the server's own objects as ``setup``
    says: the saved ones (in their last state) when the file has them, new ones when it
    has none (a server without this setup saved it), none without a setup. The setup's
    animator, and the owners of the scene's objects other than the server."""
    if setup is not None:
        scene.keeper = SERVER_KEEPER
    document = store.load() if store is not None else None
    saved_own = _holds_server_objects(document)
    # the setup's own objects, replaced by the document's of the same ids
    animator = setup(scene) if setup is not None and saved_own else None
    restored = store is not None and document is not None and \
        _restore(scene, store, saver, document)
    if setup is not None and not saved_own:
        scene.ids.forget(SERVER_OWNER)  # the setup's ids are its own to make again
        try:
            with scene.journal.transaction():
                animator = setup(scene)
        except VPError as error:  # say, a saved client object in the way: no demo then
            log.error("scene %s restored without its setup: %s", scene.name, error)
    elif setup is None and saved_own and restored:
        _forget_server_objects(scene)
    if store is not None:
        _replay(scene, store)
    return animator, sorted({owner_of(node_id) for node_id in scene.nodes} - {SERVER_OWNER})


def _restore(scene: Scene, store: SceneStore, saver: SceneSaver, document: Any) -> bool:
    """Put the scene back as ``document`` (its store's) says; whether it could. A document
    that cannot be restored is set aside, and the scene starts as its setup makes it."""
    try:
        with scene.journal.transaction():
            summary = import_scene(scene, document)
    except Exception as error:
        if not isinstance(error, VPError):  # a bug
            log.exception("restoring scene %s failed", scene.name)
        store.set_aside(error.message if isinstance(error, VPError)
                        else f"restoring it failed ({error!r})")
        return False
    saver.restored()  # as on the disk already
    log.info("scene %s restored: %d objects", scene.name, summary["objects"])
    return True


def _holds_server_objects(document: Any) -> bool:
    """Whether a saved document (checked or not yet) holds objects of the server's own."""
    nodes = document.get("nodes") if isinstance(document, dict) else None
    return isinstance(nodes, list) and any(
        isinstance(node, dict) and isinstance(node.get("id"), str)
        and owner_of(node["id"]) == SERVER_OWNER for node in nodes)


def _forget_server_objects(scene: Scene) -> None:
    """The objects of a setup this server has not are gone, with what clients attached."""
    for node in scene.roots():
        if owner_of(node.id) == SERVER_OWNER:
            scene.delete(node)
    scene.ids.forget(SERVER_OWNER)
    log.info("scene %s: the objects of a setup this server has not are gone", scene.name)


def _replay(scene: Scene, store: SceneStore) -> None:
    """Make again the changes journaled since the document was written."""
    lines = store.journal()
    if lines:
        applied, skipped = replay(scene, lines)
        scene.clock.take()  # steps replayed are not taken again: their world is gone
        log.info("scene %s: %d journaled changes made again (%d not)", scene.name,
                 applied, skipped)
