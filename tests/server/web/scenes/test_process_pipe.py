"""The loop's end of a scene's pipe speaks multiprocessing's framing: what a scene's process
sends with ``Connection.send`` arrives whole and in order however it is cut, and what the
loop sends, ``Connection.recv`` reads (a real socket pair, a real event loop)."""

import asyncio
import pickle
import socket
import threading
from multiprocessing.connection import Connection

from server.web.scenes.process_pipe import ProcessPipe, framed

VALUES = [[], ["a"], {"big": "x" * 70_000}, list(range(200_000)), "é" * 10, None]


def test_what_a_connection_sends_arrives_whole_and_in_order_and_the_end_is_told():
    async def run() -> tuple[list[object], bool]:
        mine, theirs = socket.socketpair()
        received, lost = [], asyncio.Event()
        connection = Connection(theirs.detach())
        sender = threading.Thread(target=lambda: ([connection.send(v) for v in VALUES],
                                                  connection.close()))
        transport, _ = await asyncio.get_running_loop().connect_accepted_socket(
            lambda: ProcessPipe(received.append, lost.set), mine)
        sender.start()
        await asyncio.wait_for(lost.wait(), 30)
        sender.join()
        transport.close()
        return received, lost.is_set()
    received, ended = asyncio.run(run())
    assert received == VALUES and ended


def test_what_the_loop_sends_a_connection_reads():
    async def run() -> list[object]:
        mine, theirs = socket.socketpair()
        connection = Connection(theirs.detach())
        link = ProcessPipe(lambda value: None, lambda: None)
        transport, _ = await asyncio.get_running_loop().connect_accepted_socket(lambda: link, mine)
        for value in VALUES:
            link.send(value)
        read = await asyncio.to_thread(lambda: [connection.recv() for _ in VALUES])
        transport.close()
        connection.close()
        return read
    assert asyncio.run(run()) == VALUES


def test_a_message_cut_anywhere_or_with_a_long_length_is_read_once_complete():
    received: list[object] = []
    link = ProcessPipe(received.append, lambda: None)
    body = pickle.dumps({"k": 1})
    long_form = (-1).to_bytes(4, "big", signed=True) + len(body).to_bytes(8, "big") + body
    data = framed("first") + long_form + framed(["last"])
    for k in range(len(data)):  # a byte at a time: nothing until each message is whole
        link.data_received(data[k:k + 1])
        if k < len(framed("first")) - 1:
            assert received == []
    assert received == ["first", {"k": 1}, ["last"]]
