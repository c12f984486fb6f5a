"""``synth ui [--port P] [INPUT]``: the design loop in a local web application (``synth.ui``, NiceGUI).

Opens ``INPUT`` (any design input: YAML, TOML, JSON, the Excel template, a case file) or the embedded
default application on the design page; a bad ``INPUT`` is refused as every scene refuses it (exit 2).
The server binds to 127.0.0.1 (this machine only) unless ``--host`` says otherwise, and says which.
Needs the optional dependency NiceGUI: ``pip install "synth[ui]"``.
"""

from __future__ import annotations

import socket

from synth.errors import InputError, Problem
from synth.ui import LOCAL_HOSTS, serve

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("ui", help="the design loop in a local web application (form, checks, graphs, 3D, portfolio)")
    p.add_argument("input", nargs="?", metavar="INPUT",
                   help="design input to open (default: the embedded default application)")
    p.add_argument("--port", type=int, default=8080, metavar="P", help="TCP port (default 8080)")
    p.add_argument("--host", default="127.0.0.1",
                   help="address to bind (default 127.0.0.1: this machine only; 0.0.0.0 exposes the page to the "
                        "network, with no authentication)")
    p.set_defaults(func=_main)


def _check_port(host: str, port: int) -> None:
    if not 1 <= port <= 65535:
        raise InputError(Problem("--port", port, "a TCP port in [1, 65535]"))
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as uvicorn binds: a closing connection is no user
        try:
            s.bind((host, port))
        except OSError as e:
            raise InputError(Problem("--port", port, f"a free port on {host} ({e.strerror or e})")) from None


def _main(args) -> int:
    import importlib.util
    from pathlib import Path

    from synth import schema
    from synth.io import documents
    if importlib.util.find_spec("nicegui") is None:
        raise InputError(Problem("synth ui", "NiceGUI not installed", 'pip install "synth[ui]" (or nicegui>=3)'))
    if args.input:
        values = documents.read_mapping(Path(args.input))
        schema.validate({k: v for k, v in values.items() if v is not None})  # refused here as by every scene
        source = Path(args.input).name
    else:
        from synth.ui.session import default_values
        values, source = default_values(), "default application (synth/data/default_case.yaml)"
    _check_port(args.host, args.port)
    shown = f"[{args.host}]" if ":" in args.host else args.host
    where = ("this machine only" if args.host in LOCAL_HOSTS
             else "REACHABLE FROM OTHER MACHINES, no authentication")
    print(f"synth ui: http://{shown}:{args.port}/ (bound to {args.host}: {where}); Ctrl-C stops it", flush=True)
    serve(values, source, host=args.host, port=args.port)
    return 0
