"""What a light viewer reports: frames per second, late frames and frames it never got."""

import random

from websockets.frames import Frame, Opcode

from bench.viewers import ServerFrames, summary


def test_a_pause_counts_as_late_and_missing_sequence_numbers_as_skipped():
    arrivals = [k / 60 for k in range(60)] + [1.5]  # 60 frames at 60 Hz, then a half-second gap
    seqs = list(range(1, 61)) + [90]
    found = summary(arrivals, seqs)
    assert found["frames"] == 61 and found["late"] == 1 and found["skipped"] == 29
    assert 39 < found["fps"] < 41  # 60 frames over 1.5 s
    assert summary([], []) == {"frames": 0, "fps": 0.0, "late": 0, "skipped": 0}


def _server_frame(opcode, payload):
    return Frame(opcode, payload).serialize(mask=False)  # websockets' own, as a server's


def test_the_light_viewers_split_websockets_own_server_frames_however_they_are_cut():
    texts = [b'{"op":"frame","seq":%d,"time":1}' % k for k in range(3)]
    frames = [(Opcode.TEXT, texts[0]), (Opcode.PING, b"ping!"),
              (Opcode.TEXT, texts[1] + b" " * 200),      # a 2-byte length
              (Opcode.TEXT, texts[2] + b" " * 70_000),   # an 8-byte length
              (Opcode.CLOSE, b"\x03\xe8")]
    stream = b"".join(_server_frame(opcode, payload) for opcode, payload in frames)
    want = [(opcode.value, payload) for opcode, payload in frames]
    rng = random.Random(5)
    for _ in range(50):
        cuts = sorted(rng.sample(range(1, len(stream)), rng.randint(1, 40)))
        reader, found = ServerFrames(), []
        for start, end in zip([0, *cuts], [*cuts, len(stream)]):
            found += reader.feed(stream[start:end])
        assert found == want
