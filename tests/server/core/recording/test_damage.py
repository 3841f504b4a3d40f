"""Reading a damaged recording: whatever the reader raises for a file cut short, changed
or not a recording becomes one ``recording_damaged`` error naming the recording."""

import json
import struct

import pytest
from mcap.exceptions import McapError

from server.core.kit.errors import RecordingDamaged
from server.core.recording.damage import reading


@pytest.mark.parametrize("raised", [McapError("bad magic"), struct.error("unpack requires 8 bytes"),
                                    EOFError(), json.JSONDecodeError("Expecting value", "x", 0),
                                    KeyError("seq")])
def test_what_a_damaged_file_raises_is_recording_damaged(raised):
    with pytest.raises(RecordingDamaged) as caught:
        with reading("/recordings/r-1a2b.mcap"):
            raise raised
    assert caught.value.code == "recording_damaged"
    assert caught.value.details["recording"] == "r-1a2b"
    assert caught.value.message.startswith("recording r-1a2b cannot be read: ")
    assert caught.value.message != "recording r-1a2b cannot be read: "  # it says what


def test_a_fault_of_ours_is_not_called_damage():
    with pytest.raises(ZeroDivisionError):
        with reading("/recordings/r-1.mcap"):
            1 / 0
