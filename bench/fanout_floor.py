"""The floor of a viewer-frame: one ``send`` of the same bytes on each of many loopback
TCP sockets from a Python loop, with nothing around it.

A light reader process (a child, reading with epoll) drains the other ends, as the
viewers do. What is measured is the sending thread's CPU per send: the kernel's TCP
work for the segment (loopback delivers it in the sender's context) and the loop's
bare call. The server's fan-out (``fanout_us_per_viewer_frame``) is this plus what
deciding whether a connection keeps up costs.
"""

from __future__ import annotations

import os
import selectors
import socket
import time

FRAME_BYTES = 900  # about a hands-10 frame


def send_floor_us(count: int, seconds: float, rate: float = 60.0) -> float:
    """CPU microseconds of the sending thread per send, ``count`` sockets at ``rate``."""
    listener = socket.create_server(("127.0.0.1", 0), backlog=count)
    readers, writers = [], []
    for _ in range(count):
        readers.append(socket.create_connection(listener.getsockname()))
        writers.append(listener.accept()[0])
    listener.close()
    child = os.fork()
    if child == 0:  # the reader: it never returns
        for writer in writers:
            writer.close()
        _read_until(readers, time.monotonic() + seconds + 2)
    for reader in readers:
        reader.close()
    try:
        return _send(writers, seconds, rate)
    finally:
        for writer in writers:
            writer.close()
        os.waitpid(child, 0)


def _send(writers: list[socket.socket], seconds: float, rate: float) -> float:
    frame = b"x" * FRAME_BYTES
    for writer in writers:
        writer.setblocking(False)
    time.sleep(0.5)  # the reader is reading
    start, cpu, sent = time.monotonic(), time.thread_time(), 0
    due = start
    while time.monotonic() < start + seconds:
        for writer in writers:
            try:
                sent += writer.send(frame) == len(frame)
            except BlockingIOError:  # the reader fell behind: that socket's frame is not sent
                pass
        due += 1 / rate
        time.sleep(max(0.0, due - time.monotonic()))
    return 1e6 * (time.thread_time() - cpu) / sent


def _read_until(readers: list[socket.socket], end: float) -> None:
    try:
        selector = selectors.EpollSelector()
        for reader in readers:
            reader.setblocking(False)
            selector.register(reader, selectors.EVENT_READ)
        while time.monotonic() < end:
            for key, _ in selector.select(0.1):
                try:
                    if not key.fileobj.recv(1 << 16):
                        selector.unregister(key.fileobj)
                except (BlockingIOError, ConnectionError):
                    pass
    finally:
        os._exit(0)
