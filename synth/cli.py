"""The ``synth`` command line: one sub-command per scene.

Each scene module in :data:`SCENES` exposes ``register(subparsers)`` that adds
its sub-command and sets ``func`` to a handler ``func(args) -> int``.
Input errors (:class:`synth.errors.InputError`) are printed one problem per
line on stderr with exit code 2, never as a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from synth.errors import InputError

__all__ = ["main", "SCENES"]

SCENES = [
    "synth.scenes.flowchart",
    "synth.scenes.compare",
    "synth.scenes.demo",
    "synth.scenes.shrink_fit",
    "synth.scenes.template",
    "synth.scenes.report",
    "synth.scenes.design",
    "synth.scenes.pareto",
    "synth.scenes.cad",
    "synth.scenes.bulk",
    "synth.scenes.portfolio_sample",
]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="synth", description="Timing-belt tensioner design synthesiser.")
    parser.add_argument("--catalogs", metavar="DIR", action="append", default=[],
                        help="a folder of user catalogs overriding the built-in CSVs (repeatable)")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in SCENES:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:  # a scene not built yet
            if exc.name == name:
                continue
            raise
        module.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    try:
        if args.catalogs:
            from synth import catalog
            catalog.set_user_dirs(*args.catalogs)
        return int(args.func(args) or 0)
    except BrokenPipeError:  # output piped into head & co.
        sys.stderr.close()
        return 0
    except InputError as exc:
        print("synth: invalid input", file=sys.stderr)
        for problem in exc.problems:
            print(f"  - {problem}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
