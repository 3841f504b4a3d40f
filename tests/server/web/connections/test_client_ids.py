"""One server's client ids: c1, c2, … never handed out twice, a restart on the same state
folder included, nor below the owners a document brought in; resume keys signed with a
key that outlives restarts (or, without a folder, one of this run's)."""

import asyncio

from server.web.connections.client_ids import ClientIds
from server.web.storage.state_dir import StateDir


def test_without_a_state_folder_ids_count_from_one_under_a_fresh_key():
    ids, other = ClientIds(), ClientIds()
    assert [ids.next() for _ in range(3)] == [1, 2, 3]
    ids.reserve(10)
    ids.reserve(5)  # (never back down)
    assert ids.next() == 11
    assert len(ids.secret) == 32 and ids.secret != other.secret
    asyncio.run(ids.available())  # answers at once: ids are counted here


def test_a_restart_never_hands_out_an_id_again_and_keeps_its_key(tmp_path):
    first = ClientIds(StateDir(tmp_path))
    handed = [first.next() for _ in range(5)]
    first.reserve(40)  # owners of an imported document
    handed.append(first.next())
    again = ClientIds(StateDir(tmp_path))  # the server started again (even after kill -9)
    assert again.next() > max(handed) and again.secret == first.secret
