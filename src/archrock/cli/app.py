"""``archrock app``: start the local web application (the arch in the browser; docs/app.md)."""

from __future__ import annotations

import sys

from ._parser import CLIError, out_of_range, parsed

#: The loopback address: nothing on another machine can reach the app unless --host says so.
DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8765


def _port(text: str) -> int:
    v = parsed(text, int, "an integer")
    if not 0 <= v <= 65535:
        raise out_of_range(text, "0 to 65535 (0: any free port)")
    return v


def add_app_parser(subparsers):
    p = subparsers.add_parser(
        "app", help="the arch in the browser: a local web application (needs archrock[app])",
        description="Starts a local web server and opens the page in the browser: the arch "
                    "drawn to scale, its thrust lines and collapse multipliers as its "
                    "parameters move (or a geometry file or DXF survey opened), a pulse or a "
                    "recorded ground motion played as an animation, an ensemble of irregular "
                    "arches with its histogram, PNG figures and the assessment report. Ctrl-C "
                    "stops it.")
    p.add_argument("--port", type=_port, default=DEFAULT_PORT,
                   help=f"TCP port (default {DEFAULT_PORT}; 0: any free port)")
    p.add_argument("--host", default=DEFAULT_HOST,
                   help=f"address to listen on (default {DEFAULT_HOST}: this machine only; "
                        f"0.0.0.0 opens it to the network: the app has no login; there the page "
                        f"must be opened by the machine's IP address, not a name)")
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")
    p.set_defaults(func=run_app)
    return p


def run_app(args) -> int:
    from ..app import require_app_extra

    require_app_extra()  # ImportError naming `pip install 'archrock[app]'`
    import socket
    import threading
    import webbrowser

    import uvicorn

    from ..app import create_app
    from ..app.server import server_config

    if not args.host.strip():
        raise CLIError("--host: empty; allowed an address such as 127.0.0.1")
    try:  # bind first: a port in use is a one-line error, and port 0 picks a free one
        family = socket.AF_INET6 if ":" in args.host else socket.AF_INET
        sock = socket.socket(family, socket.SOCK_STREAM)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((args.host, args.port))
        sock.listen(128)  # a request right after the URL is printed waits, not refused
    except (OSError, OverflowError) as exc:
        raise CLIError(f"--host/--port: cannot listen on {args.host}:{args.port} "
                       f"({getattr(exc, 'strerror', None) or exc})") from None
    port = sock.getsockname()[1]
    shown = "127.0.0.1" if args.host in ("0.0.0.0", "::") else args.host
    url = f"http://{shown if ':' not in shown else f'[{shown}]'}:{port}/"
    # the Host header must name this address and port (a guard against DNS rebinding); a
    # page's API calls carry the token written into the page at launch (docs/app.md)
    app = create_app(args.host, port, warm_up=True)
    print(f"archrock app: {url} (Ctrl-C stops it)", file=sys.stderr, flush=True)
    if args.host not in ("127.0.0.1", "localhost", "::1"):
        print(f"archrock app: warning: listening on {args.host}: other machines can reach it",
              file=sys.stderr)
    if not args.no_browser:
        threading.Timer(0.8, webbrowser.open, (url,)).start()
    server = uvicorn.Server(server_config(app))
    server.run(sockets=[sock])
    return 0
