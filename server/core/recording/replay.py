"""A recording read back (:mod:`.mcap_recorder`'s files): the scene as it was at any time,
and what changed between two times, as the messages a viewer applies.

Seeking does not play the file from its start: MCAP's chunk index finds the last snapshot
at or before the time (one every SNAPSHOT_EVERY seconds) and the ticks after it, whose
frames are folded into one (:func:`fold`), so a viewer gets a snapshot and one frame
whatever the time.

Times here are seconds from the recording's start (its first message).
"""

from __future__ import annotations

import json
import os
from functools import lru_cache
from typing import IO, Any, Iterator

from mcap.reader import SeekingReader, make_reader

from ..scene.frames import merge_frames
from .damage import reading

SNAPSHOTS, TICKS = "/vp/snapshot", "/vp/ticks"


class Replay:
    """The recording in ``stream`` (a seekable binary file, finished)."""

    def __init__(self, stream: IO[bytes]) -> None:
        stream.seek(0)
        self._reader: SeekingReader = make_reader(stream)  # type: ignore[assignment]
        summary = self._reader.get_summary()
        if summary is None or summary.statistics is None:
            raise ValueError("not a finished recording: it has no MCAP summary")
        self.start_ns = summary.statistics.message_start_time
        self.end_ns = summary.statistics.message_end_time

    @property
    def duration(self) -> float:
        """Seconds from the first message to the last."""
        return (self.end_ns - self.start_ns) / 1e9

    def at(self, seconds: float) -> list[dict[str, Any]]:
        """The scene at ``seconds`` (clamped to the recording): its last snapshot before
        then and the ticks after it, folded."""
        until = self._ns(seconds)
        found = next(self._messages(SNAPSHOTS, None, until, reverse=True), None)
        if found is None:
            raise ValueError("the recording has no snapshot")
        taken, snapshot = found
        later = [m for _, tick in self._messages(TICKS, taken, until)
                 for m in tick["messages"] if m["seq"] > snapshot["seq"]]
        return [snapshot, *fold(later)]

    def between(self, after: float, until: float) -> list[dict[str, Any]]:
        """What changed after ``after`` up to ``until`` (seconds), folded."""
        start, end = self._ns(after), self._ns(until)
        if end <= start:
            return []
        return fold([m for taken, tick in self._messages(TICKS, start, end) if taken > start
                     for m in tick["messages"]])

    def ticks(self, after: float, until: float) -> list[tuple[float, list[dict[str, Any]]]]:
        """Each tick after ``after`` up to ``until`` (seconds) with its messages, as they
        were sent: what a player applies one by one, at their times."""
        start, end = self._ns(after), self._ns(until)
        return [((taken - self.start_ns) / 1e9, tick["messages"])
                for taken, tick in self._messages(TICKS, start, end) if taken > start]

    def ticks_after(self, seconds: float, count: int) -> list[float]:
        """The times of the next ``count`` ticks after ``seconds`` (stepping frame by frame)."""
        times = []
        for taken, _ in self._messages(TICKS, self._ns(seconds) + 1, self.end_ns):
            times.append((taken - self.start_ns) / 1e9)
            if len(times) == count:
                break
        return times

    def _ns(self, seconds: float) -> int:
        return min(self.end_ns, max(self.start_ns, self.start_ns + round(seconds * 1e9)))

    def _messages(self, topic: str, start: int | None, end: int,
                  reverse: bool = False) -> Iterator[tuple[int, dict[str, Any]]]:
        """(log time, message) of ``topic`` with ``start`` ≤ log time ≤ ``end``."""
        for _, _, message in self._reader.iter_messages(topics=[topic], starting_at=start,
                                                        ending_at=end, reverse=reverse):
            yield message.log_time, json.loads(message.data)


@lru_cache(maxsize=8)
def _opened(path: str, version: tuple[int, int]) -> Replay:
    return Replay(open(path, "rb"))  # noqa: SIM115 (kept open while cached; a file per recording)


def opened(path: str) -> Replay:
    """The replay of the recording at ``path``, read once per version of the file in this
    process (a player asks for the next second many times)."""
    stat = os.stat(path)
    return _opened(path, (stat.st_size, stat.st_mtime_ns))


def seek(path: str, seconds: float) -> dict[str, Any]:
    """The recording at ``path`` at ``seconds``: its time, duration and the messages that
    show the scene then (what ``GET /api/recordings/{id}/at`` answers)."""
    with reading(path):
        replay = opened(path)
        clamped = min(max(0.0, seconds), replay.duration)
        return {"time": clamped, "duration": replay.duration, "messages": replay.at(clamped)}


def window(path: str, after: float, until: float) -> dict[str, Any]:
    """The ticks of the recording at ``path`` in (after, until] (``…/ticks``)."""
    with reading(path):
        return {"ticks": [[time, messages] for time, messages in opened(path).ticks(after, until)]}


def fold(messages: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Tick messages in order, consecutive frames merged into one (``added`` and
    ``removed`` stay between them, in order): their effect, applied at once."""
    out: list[dict[str, Any]] = []
    for message in messages:
        if message["op"] == "frame" and out and out[-1]["op"] == "frame":
            out[-1] = merge_frames(out[-1], message)
        else:
            out.append(message)
    return out
