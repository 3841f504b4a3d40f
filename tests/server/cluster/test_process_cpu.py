"""The CPU of real processes, as a worker measures its scenes': a busy one's share, an
idle one's, and what new ones are expected to use."""

from __future__ import annotations

import subprocess
import sys
import time
from typing import Iterator

import pytest

from server.cluster.process_cpu import ProcessCpu

BUSY = "print('ready', flush=True)\nwhile True: pass"
IDLE = "import time; print('ready', flush=True); time.sleep(60)"


def _started(code: str) -> subprocess.Popen[bytes]:
    """A Python process running ``code``, once it has started (its start takes CPU too)."""
    process = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE)
    assert process.stdout is not None and process.stdout.readline() == b"ready\n"
    return process


@pytest.fixture
def processes() -> Iterator[list[subprocess.Popen[bytes]]]:
    started = [_started(code) for code in (BUSY, IDLE)]
    yield started
    for process in started:
        process.kill()
        process.wait()


def test_each_process_has_its_share_measured_over_a_whole_look(processes):
    busy, idle = (p.pid for p in processes)
    cpu = ProcessCpu()
    cpu.measure([busy, idle])
    assert cpu.shares == {}  # seen once: nothing measured over a whole look yet
    time.sleep(0.5)
    cpu.measure([busy, idle])
    # the busy one had what the machine gave it (the suite shares its cores), the idle none
    assert cpu.shares[busy] > 0.02 > cpu.shares[idle]


def test_processes_not_yet_measured_count_at_the_mean_share_and_no_less(processes):
    busy, idle = (p.pid for p in processes)
    cpu = ProcessCpu()
    for _ in range(2):
        cpu.measure([busy, idle])
        time.sleep(0.3)
    measured = cpu.shares[busy] + cpu.shares[idle]
    new = _started(IDLE)
    try:
        # the new process and one not started yet, each at the mean of the two measured
        assert cpu.expected([busy, idle, new.pid, None], 0.01) == pytest.approx(2 * measured)
        # a burst of new ones: each at least what a new one is expected to use
        assert cpu.expected([None] * 20, 0.05) == pytest.approx(1.0)
        assert cpu.expected([idle, None], 1.0) == pytest.approx(cpu.shares[idle] + 1.0)
    finally:
        new.kill()
        new.wait()


def test_new_processes_are_expected_to_use_what_typical_ones_do(processes):
    """A worker guesses a new scene's share from its attended scenes: a busy scene whose
    client has left (its start measured) is counted as itself, not taken as typical."""
    busy, idle = (p.pid for p in processes)
    cpu = ProcessCpu()
    for _ in range(2):
        cpu.measure([busy, idle])
        time.sleep(0.3)
    assert cpu.expected([busy, None], 0.01, typical=[idle]) == \
        pytest.approx(cpu.shares[busy] + max(cpu.shares[idle], 0.01))
    assert cpu.expected([busy, None], 0.05, typical=[]) == pytest.approx(cpu.shares[busy] + 0.05)
    assert cpu.expected([busy, None], 0.01) == pytest.approx(2 * cpu.shares[busy])
