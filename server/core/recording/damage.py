"""Reading a recording that may be damaged: a file cut short, changed on the disk, or not
a recording at all (anything can land in the recordings folder).

The MCAP reader, its decompressor and the JSON inside raise many kinds of errors for such
a file, some of which cannot even be sent back from the process that read them (an error
whose arguments do not rebuild it ends a process pool). :func:`reading` turns them all
into :class:`~server.core.kit.errors.RecordingDamaged`, naming the recording and what was wrong.
"""

from __future__ import annotations

import struct
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator

from mcap.exceptions import McapError
from zstandard import ZstdError

from ..kit.errors import RecordingDamaged

# what reading a damaged file raises: the reader's own errors, the decompressor's, records
# cut short (struct, EOF), bytes that are not the JSON or the fields written (ValueError
# covers JSON's and UTF-8's errors, and a file without the summary a finished one has)
UNREADABLE = (McapError, ZstdError, struct.error, EOFError, ValueError, KeyError, IndexError,
              TypeError)


@contextmanager
def reading(path: str) -> Iterator[None]:
    """Inside: reading the recording at ``path``; what a damaged file raises is
    ``recording_damaged``."""
    try:
        yield
    except UNREADABLE as error:
        recording = Path(path).stem
        reason = str(error) or type(error).__name__
        raise RecordingDamaged(f"recording {recording} cannot be read: {reason[:200]}",
                               recording=recording) from None
