"""A real NATS server (Debian's nats-server, installed by `make test`) for the cluster's
tests, on a free loopback port with JetStream in a folder of its own; and the cluster's
processes started around it."""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import socket
import subprocess
import time
from pathlib import Path
from typing import Any, Iterator

import nats
import pytest

from server.cluster.bus import PLACE, Bus
from server.cluster.leases import lease_holder
from tests.conftest import ROOT, VP_SERVER, WAIT_SECONDS, RunningServer, free_port, start_server

NATS_SERVER = "/usr/sbin/nats-server"


class BusServer:
    """A NATS server on a free port, its JetStream in a folder: it may be killed and
    started again (the same port and store, as an operator's restart)."""

    def __init__(self, folder: Path) -> None:
        port = free_port()
        self.url = f"nats://127.0.0.1:{port}"
        self._config = folder / "nats.conf"
        self._config.write_text(f'listen: 127.0.0.1:{port}\nmax_payload: 64MB\n'
                                f'jetstream {{ store_dir: "{folder / "jetstream"}" }}\n')
        self._process: subprocess.Popen[bytes] | None = None

    def start(self) -> None:
        self._process = subprocess.Popen([NATS_SERVER, "-c", str(self._config)],
                                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        asyncio.run(_wait_for_bus(self.url))

    def kill(self) -> None:
        """``kill -9``: every connection to it breaks at once."""
        if self._process is not None:
            self._process.kill()
            self._process.wait(10)
            self._process = None

    def stop(self) -> None:
        if self._process is not None:
            self._process.terminate()
            self._process.wait(10)
            self._process = None


@contextlib.contextmanager
def running_bus(folder: Path) -> Iterator[str]:
    """A NATS server on a free port, its JetStream in ``folder``: its URL."""
    with bus_server(folder) as server:
        yield server.url


@contextlib.contextmanager
def bus_server(folder: Path) -> Iterator[BusServer]:
    """A :class:`BusServer`, running."""
    server = BusServer(folder)
    server.start()
    try:
        yield server
    finally:
        server.stop()


@pytest.fixture
def bus_url(tmp_path: Path) -> Iterator[str]:
    """A NATS server of the test's own (its buckets start empty)."""
    with running_bus(tmp_path) as url:
        yield url


async def _wait_for_bus(url: str) -> None:
    async def quiet(error: Exception) -> None:
        pass  # not listening yet: the loop tries again
    for _ in range(100):
        try:
            client = await nats.connect(url, connect_timeout=1, allow_reconnect=False,
                                        error_cb=quiet)
            await client.close()
            return
        except Exception:
            await asyncio.sleep(0.05)


def ask_bus(url: str, question: Any, lease_seconds: float = 3.0) -> Any:
    """``await question(bus)`` on a connection of its own (the first to use the bus makes
    its buckets: a worker's key then lives ``lease_seconds``)."""
    async def ask() -> Any:
        bus = await Bus.connect(url, "test", lease_seconds)
        try:
            return await question(bus)
        finally:
            await bus.close()
    return asyncio.run(ask())


def workers(url: str) -> list[str]:
    """The workers that answer on the bus, by name."""
    async def gather(bus: Bus) -> list[str]:
        return sorted(load.worker for load in await bus.gather(PLACE, None, 0.2))
    return ask_bus(url, gather)


def holder(url: str, scene: str) -> str | None:
    """The worker running ``scene``."""
    return ask_bus(url, lambda bus: lease_holder(bus.workers, bus.scenes, scene))


def start_worker(url: str, name: str, state: Path, log: Path,
                 *extra: str) -> subprocess.Popen[bytes]:
    """``vp-server --role worker`` (``extra``: more flags), answering on the bus before this
    returns."""
    output = open(log, "ab")  # noqa: SIM115 (the process keeps it)
    process = subprocess.Popen([str(VP_SERVER), "--bus", url, "--role", "worker",
                                "--worker-name", name, "--state-dir", str(state), "--no-demo",
                                "--log-level", "warning", *extra], cwd=ROOT, stdout=output,
                               stderr=output, start_new_session=True)
    deadline = time.monotonic() + WAIT_SECONDS
    while name not in workers(url):
        if process.poll() is not None or time.monotonic() > deadline:
            raise RuntimeError(f"worker {name} did not start: {log.read_text()[-2000:]}")
        time.sleep(0.1)
    return process


def start_gateway(url: str, state: Path, log: Path, *extra: str) -> RunningServer:
    """``vp-server --role gateway`` on a free port (``extra``: more flags)."""
    return start_server("--bus", url, "--role", "gateway", "--state-dir", str(state),
                        "--no-demo", *extra, log=log)


class Cluster:
    """A bus, two workers (wa, wb) and two gateways sharing one state folder, as the issue's
    smallest cluster; every process is killed at the end."""

    def __init__(self, url: str, folder: Path, *extra: str, gateways: int = 2,
                 worker_extra: tuple[str, ...] = ()) -> None:
        self.url, self.state = url, folder / "state"
        self.logs = folder
        self._extra, self._worker_extra = extra, worker_extra
        self.workers: dict[str, subprocess.Popen[bytes]] = {}
        for name in ("wa", "wb"):
            self.add_worker(name)
        self.gateways = [start_gateway(url, self.state, folder / f"g{k}.log", *extra)
                         for k in range(1, gateways + 1)]

    def add_worker(self, name: str) -> None:
        """One more worker (``extra`` flags, then ``worker_extra``)."""
        self.workers[name] = start_worker(self.url, name, self.state, self.logs / f"{name}.log",
                                          *self._extra, *self._worker_extra)

    def kill_worker(self, name: str) -> None:
        """``kill -9`` a worker and its scenes' processes: nothing is saved on the way."""
        process = self.workers.pop(name)
        os.killpg(process.pid, signal.SIGKILL)
        process.wait(10)

    def close(self) -> None:
        for process in [*self.workers.values(), *(g.process for g in self.gateways)]:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(process.pid, signal.SIGKILL)
            process.wait(10)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Cluster]:
    """One cluster for a test module (its tests run in order: a module's last may kill parts)."""
    folder = tmp_path_factory.mktemp("cluster")
    with running_bus(folder) as url:
        running = Cluster(url, folder)
        yield running
        running.close()


@pytest.fixture(scope="module")
def workers_only(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Cluster]:
    """The bus and the two workers, no gateway (the test is one)."""
    folder = tmp_path_factory.mktemp("cluster")
    with running_bus(folder) as url:
        running = Cluster(url, folder, gateways=0)
        yield running
        running.close()


NGINX = "/usr/sbin/nginx"


@contextlib.contextmanager
def load_balancer(ports: list[int], folder: Path) -> Iterator[int]:
    """Debian's nginx in front of gateways (WebSockets proxied; a gateway that refuses
    connections is passed over), as a deployment has: its port."""
    port = free_port()
    upstreams = "".join(f"server 127.0.0.1:{p} max_fails=1 fail_timeout=10s; " for p in ports)
    temp = " ".join(f"{kind}_temp_path {folder / kind};"
                    for kind in ("client_body", "proxy", "fastcgi", "uwsgi", "scgi"))
    config = folder / "nginx.conf"
    config.write_text(f"""
daemon off; master_process off; pid {folder / 'nginx.pid'}; error_log {folder / 'nginx.log'};
events {{}}
http {{
  access_log off; {temp}
  upstream gateways {{ {upstreams} }}
  map $http_upgrade $connection_upgrade {{ default upgrade; '' close; }}
  server {{
    listen 127.0.0.1:{port};
    location / {{
      proxy_pass http://gateways; proxy_http_version 1.1;
      proxy_set_header Upgrade $http_upgrade; proxy_set_header Connection $connection_upgrade;
      proxy_set_header Host $host; proxy_read_timeout 1h; proxy_connect_timeout 2s;
      proxy_next_upstream error timeout;
    }}
  }}
}}
""")
    process = subprocess.Popen([NGINX, "-c", str(config), "-p", str(folder)],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + WAIT_SECONDS
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
                break
            except OSError:
                assert time.monotonic() < deadline, (folder / "nginx.log").read_text()
                time.sleep(0.05)
        yield port
    finally:
        process.terminate()
        process.wait(10)
