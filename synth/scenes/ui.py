"""``synth ui [--port P] [--host H] [INPUT]``: the design loop in a local web application (``synth.ui``, NiceGUI).

Opens ``INPUT`` (any design input: YAML, TOML, JSON, the Excel template, a case file) or the embedded
default application on the design page, judged under the input's design rules (its ``rules:`` section, shown
in the page); a bad ``INPUT`` or bad rules are refused as every scene refuses them (exit 2).
The server binds to 127.0.0.1 (this machine only) unless ``--host`` says otherwise, and says which; bound
beyond the loopback it asks for a token made at launch, in the URL it prints (``synth.ui.guard``).
SIGTERM stops it as Ctrl-C does, a running job with it: exit 143 (130 on Ctrl-C).
Needs the optional dependency NiceGUI: ``pip install "synth[ui]"``.
"""

from __future__ import annotations

import socket

from synth.errors import InputError, Problem

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("ui", help="the design loop in a local web application (form, checks, graphs, 3D, portfolio)")
    p.add_argument("input", nargs="?", metavar="INPUT",
                   help="design input to open (default: the embedded default application); its rules: section "
                        "is applied")
    p.add_argument("--port", type=int, default=8080, metavar="P", help="TCP port (default 8080)")
    p.add_argument("--host", default="127.0.0.1",
                   help="address to bind (default 127.0.0.1: this machine only); beyond the loopback (0.0.0.0: "
                        "every interface) the page asks for the token in the URL the server prints")
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
    from synth.design.rules import NONE, read_rules
    from synth.io import documents
    if importlib.util.find_spec("nicegui") is None:
        raise InputError(Problem("synth ui", "NiceGUI not installed", 'pip install "synth[ui]" (or nicegui>=3)'))
    rules = NONE
    if args.input:
        values = documents.read_mapping(Path(args.input))
        schema.validate({k: v for k, v in values.items() if v is not None})  # refused here as by every scene
        rules = read_rules(Path(args.input), "input file", section_only=True)
        source = Path(args.input).name
    else:
        from synth.ui.session import default_values
        values, source = default_values(), "default application (synth/data/default_case.yaml)"
    _check_port(args.host, args.port)
    from synth.ui import serve
    from synth.ui.guard import Policy, is_loopback
    policy = Policy.of(args.host, args.port)
    where = ("this machine only" if is_loopback(args.host)
             else "REACHABLE FROM OTHER MACHINES: open it with the token in this URL")
    print(f"synth ui: {policy.url()} (bound to {args.host}: {where}); Ctrl-C stops it", flush=True)
    try:
        serve(values, source, host=args.host, port=args.port, rules=rules, policy=policy)
    except KeyboardInterrupt:  # SIGTERM or Ctrl-C, after the server stopped: the command line says so, exit 143/130
        import gc
        gc.freeze()  # the pages' objects are left to the process's end, not collected one by one (1-2 s)
        raise
    return 0
