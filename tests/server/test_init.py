"""The server package: a scene's process computes on one thread."""

import os
import subprocess
import sys


def _threads_after_a_matrix_product(environment: dict[str, str]) -> tuple[int, str]:
    """The threads of a process that imported the server and multiplied two matrices, and
    the OpenBLAS thread count it had then."""
    code = ("import server, numpy, os\n"
            "numpy.ones((300, 300)) @ numpy.ones((300, 300))\n"
            "print(len(os.listdir('/proc/self/task')), os.environ['OPENBLAS_NUM_THREADS'])")
    threads, asked = subprocess.run([sys.executable, "-c", code], env=environment,
                                    capture_output=True, text=True, check=True).stdout.split()
    return int(threads), asked


def test_numpy_runs_no_threads_of_its_own_beside_a_scene():
    environment = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    assert _threads_after_a_matrix_product(environment) == (1, "1")


def test_a_callers_own_thread_count_stands():
    threads, asked = _threads_after_a_matrix_product({**os.environ, "OPENBLAS_NUM_THREADS": "2"})
    # OpenBLAS runs no more threads than the process may use cores (one under taskset)
    assert asked == "2" and threads == min(2, len(os.sched_getaffinity(0)))
