"""A message made once in a scene's process: its text travels, its frame is made once."""

import pickle

from websockets.frames import Frame, Opcode
from websockets.streams import StreamReader

from server.web.connections.outgoing import Outgoing, frame_of


def test_a_message_travels_as_its_text_and_is_decoded_again_only_when_read():
    sent = Outgoing.of({"op": "frame", "seq": 1, "angles": {"c1.m": 0.5}})
    data = pickle.dumps(sent)
    assert data.count(b"angles") == 1  # the text alone, not the decoded message beside it
    received = pickle.loads(data)
    assert (received.op, received.text) == (sent.op, sent.text)
    assert received.message == {"op": "frame", "seq": 1, "angles": {"c1.m": 0.5}}


def test_a_message_is_framed_once_unmasked_and_whole():
    item = Outgoing.of({"op": "ok", "id": 3, "text": "é"})
    assert item.frame is item.frame  # the same bytes for every connection
    reader = StreamReader()
    reader.feed_data(item.frame)
    parser = Frame.parse(reader.read_exact, mask=False)
    try:
        next(parser)
    except StopIteration as done:
        frame = done.value
    assert frame.opcode == Opcode.TEXT and frame.fin and frame.data.decode() == item.text
    assert frame_of(item.text) == item.frame
