"""What a light viewer reports: frames per second, late frames and frames it never got."""

import asyncio
import random
import time

from websockets.frames import Frame, Opcode
from websockets.uri import parse_uri

from bench.viewers import ServerFrames, Viewer, summary
from tests.conftest import WAIT_SECONDS, start_server, stop_server


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


def test_a_light_viewer_answers_the_servers_pings_and_keeps_getting_frames():
    # a ping a second, each answer due within the second: four in the 4 s watched (0.5 s was
    # as tight as the test process's own loop on a loaded machine)
    running = start_server("--no-demo", "--ping-seconds", "1")
    try:
        viewer, lost = asyncio.run(_view(f"{running.ws}/ws?scene=pinged&role=viewer", 4.0))
    finally:
        stop_server(running)
    assert not lost  # the server would have closed it after a ping with no answer
    assert viewer.first_frame.result() and len(viewer.arrivals) > 20
    assert viewer.seqs == sorted(set(viewer.seqs))  # each frame once, in order


async def _view(url: str, seconds: float) -> tuple[Viewer, bool]:
    """A viewer's frames over ``seconds`` from its first (the scene's process may take a
    loaded machine seconds to start); whether the connection was lost by then."""
    window: list[float] = []
    uri = parse_uri(url)
    transport, viewer = await asyncio.get_running_loop().create_connection(
        lambda: Viewer(url, window), uri.host, uri.port)
    await asyncio.wait_for(asyncio.shield(viewer.first_frame), WAIT_SECONDS)
    window.extend([time.monotonic(), time.monotonic() + seconds])
    await asyncio.sleep(seconds)
    lost = transport.is_closing()
    transport.close()
    return viewer, lost
