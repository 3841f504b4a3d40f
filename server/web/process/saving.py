"""Keeping a scene on disk from its process: every change journaled before it is
acknowledged, the document written now and then, and a word when either cannot be done.

A change is *durable* once its journal line is written (:meth:`SceneSaver.commit`, called
before answers leave the process) or the document holding it is. While the journal cannot
be written the scene's changes are *at risk*: its clients are warned (``warning`` with
``not_saved``), ``/api/metrics`` and ``/api/health`` say so, and the server's exit code says
so if they are still at risk when it stops. A document that cannot be written while the
journal can is reported too (metrics, health, the log) but loses nothing.
"""

from __future__ import annotations

import logging
import time
from typing import Any, Callable

from ...core.protocol.command_log import applied_line, left_line
from ...core.protocol.scene_document import encode_document, export_scene
from ...core.protocol.session import Session
from ...core.scene.scene import Scene
from ..storage.scene_store import SceneStore

log = logging.getLogger(__name__)
SAVE_SECONDS = 1.0  # a changed scene's document is written at most this often (and at stop)
SAVE_SHARE = 0.02  # ...and less often when writing it takes longer than this share of the time
# ...but at least this often: in the suite, one save of a hand's lab stretched to 2.2 s by
# the disk's fsyncs (the other tests' writes) put the next 111 s away, and metrics said
# "not saved" for as long after the last change (the journal kept every change meanwhile)
SAVE_SECONDS_MOST = 15.0
FLUSH_SECONDS = 1.0  # the journal reaches the disk itself (past a power cut) this often
JOURNAL_BYTES = 16 << 20  # a journal this long is folded into a new document at once
Tell = Callable[[str, str], None]  # (code, message): a warning for the scene's clients
Report = Callable[[dict[str, Any]], None]  # what report() says, whenever that changes


def save_interval(took: float) -> float:
    """Seconds from a save that took ``took`` seconds to the next one a changed scene gets."""
    return min(SAVE_SECONDS_MOST, max(SAVE_SECONDS, took / SAVE_SHARE))


class SceneSaver:
    """The durable side of one scene (with ``store`` None: a scene that is not kept)."""

    def __init__(self, scene: Scene, store: SceneStore | None, tell: Tell,
                 reported: Report = lambda report: None) -> None:
        self.scene = scene
        self.store = store
        self._tell = tell
        self._reported = reported
        self._pending = bytearray()  # journal lines of changes applied, not yet written
        self._saved = (scene.revision, 0.0)  # revision in the document, and when (monotonic)
        self._every = SAVE_SECONDS
        self._flushed = 0.0
        self.error: str | None = None  # what the last write that failed said, while it lasts
        self.at_risk = False  # changes exist only in memory (the journal could not be written)

    # --- changes ---------------------------------------------------------------------------

    def changed(self, session: Session, message: dict[str, Any]) -> None:
        """A client's request changed the scene: its journal line waits for :meth:`commit`."""
        if self.store is not None:
            self._pending += applied_line(session.client_id, session.operations.keep, message)

    def left(self, client_id: str) -> None:
        """A client's objects went when its grace period ended."""
        if self.store is not None:
            self._pending += left_line(client_id)

    def commit(self) -> None:
        """Write the waiting journal lines (before the answers to their requests go out)."""
        if not self._pending or self.store is None:
            return
        lines, self._pending = bytes(self._pending), bytearray()
        try:
            self.store.append(lines)
        except OSError as error:
            self._failed(f"its journal cannot be written ({error.strerror or error})",
                         at_risk=True)

    # --- documents -------------------------------------------------------------------------

    @property
    def saved(self) -> bool | None:
        """Whether the document holds every change (None: the scene is not kept); not
        while a change waits for its tick (the revision counts ticks that sent changes)."""
        if self.store is None:
            return None
        return self._saved[0] == self.scene.revision and not self.scene.feed.pending

    def restored(self) -> None:
        """The scene was just made from its document: the document is up to date."""
        self._saved = (self.scene.revision, time.monotonic())

    def tick(self, now: float) -> None:
        """Between ticks: flush the journal now and then, write the document when due."""
        if self.store is None:
            return
        if now - self._flushed >= FLUSH_SECONDS:
            self._flushed = now
            try:
                self.store.flush()
            except OSError as error:
                self._failed(f"its journal cannot be flushed ({error.strerror})", at_risk=True)
        due = now - self._saved[1] >= self._every or self.store.journal_bytes > JOURNAL_BYTES
        if due and not self.saved:
            self.save()

    def save(self, replaced: bool = False) -> bool:
        """Write the document if it is out of date (``replaced``: the whole scene was, so
        the journal no longer follows its document); whether everything is on the disk."""
        if self.store is None or (self.saved and not replaced):
            return not self.at_risk
        self.commit()
        revision, started = self.scene.revision, time.perf_counter()
        try:
            self.store.save(encode_document(export_scene(self.scene, embed_assets=False)))
        except Exception as error:  # a full or read-only disk, say: the next save tries again
            if not isinstance(error, OSError):  # a bug
                log.exception("saving scene %s failed", self.scene.name)
            if replaced:
                self.store.forget_journal()  # its lines would apply to the old document
            # clients' changes are in the journal; an import's (which has none) is not
            self._failed(f"its file cannot be written ({getattr(error, 'strerror', None) or error})",
                         at_risk=replaced)
            self._saved = (self._saved[0], time.monotonic())
            return not self.at_risk
        self._every = save_interval(time.perf_counter() - started)
        self._saved = (revision, time.monotonic())
        self._recovered()
        return True

    def close(self) -> bool:
        """The scene stops: everything written if it can be; whether nothing is at risk."""
        durable = self.save()
        if self.store is not None:
            self.store.close()
        return durable

    # --- reporting -------------------------------------------------------------------------

    def report(self) -> dict[str, Any]:
        """What metrics say of the scene's files."""
        return {"saved": self.saved, "durable": None if self.store is None else not self.at_risk,
                "saveError": self.error}

    def _failed(self, reason: str, at_risk: bool) -> None:
        """Note a failure; the log, clients and metrics hear of a new failure once, and of
        changes coming to be at risk once (not of every retry, whatever it says)."""
        news = self.error is None or (at_risk and not self.at_risk)
        self.error = reason
        if not news:
            return
        log.error("scene %s: %s%s", self.scene.name, reason,
                  "; its changes last only until the server stops" if at_risk else
                  "; clients' changes are kept in its journal")
        if at_risk and not self.at_risk:
            self.at_risk = True
            self._tell("not_saved", f"changes to scene {self.scene.name} cannot be saved: "
                                    f"{reason}; they last only until the server stops")
        self._reported(self.report())

    def _recovered(self) -> None:
        if self.error is None:
            return
        log.info("scene %s is saved again", self.scene.name)
        if self.at_risk:
            self._tell("saved", f"scene {self.scene.name} is saved again, with every change")
        self.error, self.at_risk = None, False
        self._reported(self.report())
