"""A message a scene's process made, as its connections send it: encoded once, framed
once. No asyncio here: scenes' processes make these (:mod:`server.web.process.worker`)."""

from __future__ import annotations

import json
import weakref
from typing import Any

from websockets.frames import Frame, Opcode

from ...core.protocol.messages import encode
from ...core.scene.frames import merge_frames


def frame_of(text: str) -> bytes:
    """A text message as one whole, unmasked WebSocket frame."""
    return Frame(Opcode.TEXT, text.encode()).serialize(mask=False, extensions=[])


class Outgoing:
    """A message's JSON text and op, encoded once however many connections get it.

    Made in a scene's process and sent to the server's as text; framed for the WebSocket
    once, here, when first sent; decoded again only where it is needed (folding frames
    for a slow reader).
    """

    __slots__ = ("op", "text", "_message", "_frame", "_behind", "__weakref__")

    def __init__(self, op: str, text: str, message: dict[str, Any] | None = None) -> None:
        self.op = op
        self.text = text
        self._message = message
        self._frame: bytes | None = None
        # a frame this one was folded behind (weakly: a strong key would chain every frame
        # to the one before, for ever) -> the fold
        self._behind: weakref.WeakKeyDictionary[Outgoing, Outgoing] | None = None

    @classmethod
    def of(cls, message: dict[str, Any]) -> Outgoing:
        return cls(message["op"], encode(message), message)

    @property
    def message(self) -> dict[str, Any]:
        if self._message is None:
            self._message = json.loads(self.text)
        return self._message

    @property
    def frame(self) -> bytes:
        """The message as one WebSocket frame: the same bytes for every connection."""
        if self._frame is None:
            self._frame = frame_of(self.text)
        return self._frame

    def behind(self, older: Outgoing) -> Outgoing:
        """This frame folded behind ``older`` (both frames), made once for every connection
        that has ``older`` waiting: readers that fall behind together (a swamped server,
        its viewers reading slowly) would otherwise each decode, merge and encode the same
        two frames, the more the further behind."""
        if self._behind is None:
            self._behind = weakref.WeakKeyDictionary()
        fold = self._behind.get(older)
        if fold is None:
            fold = self._behind[older] = Outgoing.of(merge_frames(older.message, self.message))
        return fold

    def __reduce__(self) -> tuple[Any, ...]:
        return Outgoing, (self.op, self.text)  # the text travels, not the decoded message
