"""Work beside the scenes: one process a kind, below their priority, bounded in number."""

import asyncio
import os
import time
from pathlib import Path

import pytest

from server.core.kit.errors import LimitExceeded, OutOfRange
from server.web.scenes.offload import CallerGone, Offload
from tests.conftest import WAIT_SECONDS, alive


def wait_for(path: str) -> int:
    """Runs in the offload's process: until ``path`` exists; that process's niceness."""
    deadline = time.monotonic() + WAIT_SECONDS
    while not Path(path).exists():
        assert time.monotonic() < deadline
        time.sleep(0.01)
    return os.nice(0)


def test_past_its_limit_a_call_is_refused_naming_the_limit_and_the_others_finish(tmp_path):
    # three resimulations at once ran one at a time with no bound on waiting callers
    async def scenario():
        offload = Offload(("resimulations", 2), "resimulations", nice=10)
        go = tmp_path / "go"
        running = [asyncio.ensure_future(offload.run(wait_for, str(go))) for _ in range(2)]
        await asyncio.sleep(0)  # both taken in
        with pytest.raises(LimitExceeded) as refused:
            await offload.run(wait_for, str(go))
        go.touch()
        done = await asyncio.gather(*running)
        offload.close()
        return refused.value, done, offload.waiting

    refusal, done, waiting = asyncio.run(scenario())
    assert refusal.details["limit"] == "resimulations" and refusal.details["value"] == 2
    assert "--limit resimulations=N" in refusal.message
    assert done == [os.nice(0) + 10] * 2 and waiting == 0  # below the server, and done


def own_pid_then_wait(started: str) -> None:
    """Runs in a call's own process: says its pid, then works until it is ended."""
    Path(started + ".part").write_text(str(os.getpid()))
    os.replace(started + ".part", started)  # whole when seen (a reader found it empty)
    time.sleep(WAIT_SECONDS)


def raises_out_of_range() -> None:
    raise OutOfRange("x must be positive", argument="x")


def test_a_call_whose_caller_hangs_up_is_ended_and_the_next_runs(tmp_path):
    # a resimulation's caller hung up: its minutes of work went on, and the next waited
    started = tmp_path / "started"

    async def scenario():
        offload = Offload(("resimulations", 2), "resimulations", nice=10, per_call=True)
        gone = asyncio.Event()
        call = asyncio.ensure_future(offload.run(own_pid_then_wait, str(started),
                                                 hung_up=gone.wait))
        while not started.exists():
            await asyncio.sleep(0.01)
        pid = int(started.read_text())
        gone.set()
        with pytest.raises(CallerGone):
            await call
        with pytest.raises(OutOfRange, match="x must be positive") as error:
            await offload.run(raises_out_of_range)  # errors come back as the errors they are
        return pid, offload.waiting, error.value.details

    pid, waiting, details = asyncio.run(scenario())
    assert not alive(pid) and waiting == 0 and details == {"argument": "x"}
