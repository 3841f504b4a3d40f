"""``vp-server``: run the Virtual Prosthetics server."""

from __future__ import annotations

import argparse
import logging

import uvicorn

from .demo import setup_diggers
from .web.app import create_app

WS_MAX_BYTES = 16 << 20  # beyond the protocol's 1 MiB: those get an answer, not a hang-up


def main(argv: list[str] | None = None) -> None:
    """Parse the command line and serve until interrupted."""
    parser = argparse.ArgumentParser(prog="vp-server", description=__doc__)
    parser.add_argument("--host", default="127.0.0.1", help="address to listen on")
    parser.add_argument("--port", type=int, default=8000, help="port to listen on")
    parser.add_argument("--no-demo", action="store_true",
                        help="start with an empty default scene (no Diggers)")
    parser.add_argument("--tick-rate", type=float, default=60.0,
                        help="scene ticks (frames) per second")
    parser.add_argument("--log-level", default="info",
                        choices=["critical", "error", "warning", "info", "debug"])
    args = parser.parse_args(argv)
    if not 1 <= args.tick_rate <= 1000:
        parser.error("--tick-rate must be between 1 and 1000")
    logging.basicConfig(level=args.log_level.upper())
    app = create_app(tick_rate=args.tick_rate, setup=None if args.no_demo else setup_diggers)
    uvicorn.run(app, host=args.host, port=args.port, ws_max_size=WS_MAX_BYTES,
                log_level=args.log_level)


if __name__ == "__main__":
    main()
