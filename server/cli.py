"""``vp-server``: run the Virtual Prosthetics server."""

from __future__ import annotations

import argparse
import asyncio
import logging
import os
import resource
import sys
from pathlib import Path

import uvicorn

from .cluster.roles import LEASE_SECONDS, ROLES, ClusterMember, WorkerSettings, plain_name
from .core.kit.limits import DEFAULT, Limits
from .core.physics.assets import AssetLibrary
from .demo import DEMOS
from .web.http.access import AccessPolicy
from .web.http.app import create_app
from .web.connections.connection_limits import ConnectionCount, guarded_protocol
from .web.connections.framed_socket import FramedSocketProtocol
from .web.scenes.runner import start_fork_server
from .web.scenes.scene_capacity import machine_memory, scenes_held

WS_MAX_BYTES = 16 << 20  # beyond the protocol's 1 MiB: those get an answer, not a hang-up
PING_SECONDS = 20.0  # a WebSocket whose peer does not answer a ping this long is closed
UNSAVED = 4  # exit code: the server stopped with changes of some scene it could not save
log = logging.getLogger("vp-server")


def main(argv: list[str] | None = None) -> None:
    """Parse the command line and serve until interrupted."""
    parser = _parser()
    args = parser.parse_args(argv)
    if not 1 <= args.tick_rate <= 1000:
        parser.error("--tick-rate must be between 1 and 1000")
    if args.view_token and not args.token:
        parser.error("a view token without a control token would leave controlling open")
    try:
        limits = _defaults().with_values(args.limit)
    except ValueError as error:
        parser.error(str(error))
    logging.basicConfig(level=args.log_level.upper())
    _raise_file_limit(limits)
    start_fork_server()  # before any thread: scenes then start from a fork of this process
    cluster = _cluster(args, limits)
    if cluster is not None and args.role == "worker":
        sys.exit(UNSAVED if asyncio.run(cluster.serve()) else 0)
    access = AccessPolicy.serving(args.host, args.token or None, args.view_token or None,
                                  tuple(args.allow_origin), tuple(args.allow_host))
    app = create_app(tick_rate=args.tick_rate, setups=None if args.no_demo else DEMOS,
                     limits=limits, uploads=args.assets_dir, access=access,
                     state_dir=args.state_dir, cluster=cluster)
    # No permessage-deflate: it would compress every frame for every client on the one
    # event loop all scenes share (a 100-hand "added" held it 55 ms; see bench/RESULTS.md),
    # and a frame made once could no longer be written to every viewer (framed_socket.py).
    uvicorn.run(app, host=args.host, port=args.port, log_level=args.log_level,
                http=guarded_protocol(limits, ConnectionCount()), ws=FramedSocketProtocol,
                ws_max_size=WS_MAX_BYTES, ws_per_message_deflate=False, ws_ping_interval=args.ping_seconds,
                ws_ping_timeout=args.ping_seconds,
                h11_max_incomplete_event_size=limits.header_bytes)
    if app.state.unsaved:
        log.error("the last changes of scene %s could not be saved",
                  ", ".join(app.state.unsaved))
        sys.exit(UNSAVED)


def _cluster(args: argparse.Namespace, limits: Limits) -> ClusterMember | None:
    """This process's part in a cluster, when ``--bus`` names one."""
    if not args.bus:
        return None
    uploads = args.assets_dir or (args.state_dir / "assets" if args.state_dir else None)
    settings = WorkerSettings(limits, args.tick_rate, AssetLibrary(uploads=uploads, limits=limits),
                              {} if args.no_demo else DEMOS, args.state_dir,
                              **({"name": plain_name(args.worker_name)} if args.worker_name else {}),
                              **({"cores": args.worker_cores} if args.worker_cores else {}))
    return ClusterMember(args.bus, args.role, settings, args.lease_seconds)


def _defaults() -> Limits:
    """The limits by default on this machine: as many scenes as its memory holds."""
    return DEFAULT.with_values([f"scenes={scenes_held(machine_memory())}"])


def _raise_file_limit(limits: Limits) -> None:
    """Open files enough for every allowed connection, or a warning that there are not."""
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    wanted = limits.connections + 2 * limits.scenes + 256  # scenes' pipes, logs, the socket
    if soft < wanted:
        new = wanted if hard == resource.RLIM_INFINITY else min(wanted, hard)
        resource.setrlimit(resource.RLIMIT_NOFILE, (new, hard))
        if new < wanted:
            log.warning("only %d open files allowed; fewer than %d connections will fit",
                        new, limits.connections)


def _parser() -> argparse.ArgumentParser:
    """The command line: every flag with its default and what it does."""
    parser = argparse.ArgumentParser(prog="vp-server", description=__doc__)
    parser.add_argument("--host", default="127.0.0.1", help="address to listen on")
    parser.add_argument("--port", type=int, default=8000, help="port to listen on")
    parser.add_argument("--no-demo", action="store_true",
                        help="start with an empty default scene (no Diggers)")
    parser.add_argument("--tick-rate", type=float, default=60.0,
                        help="scene ticks (frames) per second")
    parser.add_argument("--limit", action="append", default=[], metavar="NAME=N",
                        help=f"change a limit (repeatable); the limits and defaults: "
                             f"{', '.join(f'{k}={v}' for k, v in _defaults().wire().items())}")
    parser.add_argument("--ping-seconds", type=float, default=PING_SECONDS,
                        help="ping WebSockets this often; close those that stay silent as long")
    parser.add_argument("--assets-dir", type=Path, default=None, metavar="DIR",
                        help="keep uploaded mesh files here (default: a temporary folder "
                             "removed when the server stops)")
    parser.add_argument("--state-dir", type=Path, default=os.environ.get("VP_STATE_DIR"),
                        metavar="DIR", help="keep every scene here: each change journaled "
                        "before it is acknowledged, the scene's document written at most once "
                        "a second and on shutdown; scenes come back from here when first used; "
                        "uploads are kept here too unless --assets-dir says otherwise (default: "
                        "$VP_STATE_DIR; unset: scenes last as long as the server). Exit code 4: "
                        "some scene's last changes could not be saved")
    parser.add_argument("--token", default=os.environ.get("VP_TOKEN"), metavar="TOKEN",
                        help="controlling (WebSockets with ?token=, REST changes with "
                             "Authorization: Bearer) needs this token (default: $VP_TOKEN)")
    parser.add_argument("--view-token", default=os.environ.get("VP_VIEW_TOKEN"), metavar="TOKEN",
                        help="viewing needs this token or the control token (default: "
                             "$VP_VIEW_TOKEN; unset: viewing is open)")
    parser.add_argument("--allow-origin", action="append", metavar="ORIGIN",
                        default=[o for o in os.environ.get("VP_ALLOWED_ORIGINS", "").split(",") if o],
                        help="browser pages of this origin (https://host:port; * for any) may "
                             "connect and read REST (CORS) besides this server's own and, "
                             "when it listens on loopback, any loopback page's (repeatable; "
                             "default: $VP_ALLOWED_ORIGINS, comma-separated)")
    parser.add_argument("--allow-host", action="append", metavar="NAME",
                        default=[h for h in os.environ.get("VP_ALLOWED_HOSTS", "").split(",") if h],
                        help="answer requests that name this server NAME (its Host header) "
                             "besides its IP addresses, localhost and --host (repeatable; * "
                             "for any; default: $VP_ALLOWED_HOSTS, comma-separated)")
    parser.add_argument("--bus", default=os.environ.get("VP_BUS"), metavar="URL",
                        help="run as part of a cluster on this NATS server (nats://host:port): "
                             "scenes run on workers, clients connect to gateways (default: "
                             "$VP_BUS; unset: one server runs everything, no bus)")
    parser.add_argument("--role", choices=ROLES, default="all",
                        help="with --bus: gateway (WebSockets, REST, pages), worker (runs "
                             "scenes) or all (both in this process)")
    parser.add_argument("--worker-name", default=None, metavar="NAME",
                        help="with --bus: this worker's name (default: host name and process id)")
    parser.add_argument("--worker-cores", type=float, default=None, metavar="N",
                        help="with --bus: the cores this worker's scenes may use; it takes no "
                             "new scene that would bring them past 80 %% of them (default: the machine's)")
    parser.add_argument("--lease-seconds", type=float, default=LEASE_SECONDS,
                        help="with --bus: a dead worker's scenes start on another worker "
                             "within this long")
    parser.add_argument("--log-level", default="info",
                        choices=["critical", "error", "warning", "info", "debug"])
    return parser


if __name__ == "__main__":  # after every definition: python -m server.cli
    main()
