"""The default number of scenes follows the memory of the machine (or its container)."""

import json

from websockets.sync.client import connect

from server.web.scenes.scene_capacity import FEWEST, MOST, SCENE_BYTES, machine_memory, scenes_held
from tests.conftest import WAIT_SECONDS, start_server, stop_server


def test_scenes_held_is_a_share_of_memory_at_an_idle_scene_each_within_bounds():
    assert scenes_held(24 << 30) == 210  # this project's machines
    assert scenes_held(1 << 30) == FEWEST and scenes_held(None) == FEWEST
    assert scenes_held(1 << 40) == MOST
    assert scenes_held(100 * SCENE_BYTES) == 60


def test_a_container_bound_smaller_than_the_machine_wins(tmp_path):
    proc, cgroup = tmp_path / "proc", tmp_path / "cgroup"
    proc.mkdir(), cgroup.mkdir()
    (proc / "meminfo").write_text("MemTotal:       25165824 kB\nMemFree: 1 kB\n")
    assert machine_memory(proc, cgroup) == 24 << 30
    (cgroup / "memory.max").write_text("max\n")
    assert machine_memory(proc, cgroup) == 24 << 30
    (cgroup / "memory.max").write_text(f"{4 << 30}\n")
    assert machine_memory(proc, cgroup) == 4 << 30
    assert machine_memory(tmp_path / "nowhere", cgroup) is None


def test_the_server_says_its_default_in_hello_and_a_flag_still_changes_it():
    for flags, expected in (((), scenes_held(machine_memory())), (("--limit", "scenes=7"), 7)):
        server = start_server("--no-demo", *flags)
        try:
            with connect(f"{server.ws}/ws?scene=capacity") as ws:
                assert json.loads(ws.recv(timeout=WAIT_SECONDS))["limits"]["scenes"] == expected
        finally:
            stop_server(server)
