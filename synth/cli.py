"""The ``synth`` command line (also ``python -m synth``): one sub-command per scene.

Scenes are registered in :data:`SCENES` by name, module and one-line help,
without importing their modules: ``synth --help`` and ``synth --version``
import neither pandas, scipy, matplotlib, cadquery, pyomo, dask nor numba.
The chosen scene's module is imported only when it runs (or when its own
``--help`` is asked); it exposes ``register(sub)``, which calls
``sub.add_parser(name, help=...)`` and sets ``func`` to a handler
``func(args) -> int`` on the parser it gets.

Each scene parses its own arguments with its own parser (``prog`` ``synth
NAME``), so a bad flag prints that scene's usage; a misspelt scene gets
"did you mean". Every ``--json`` flag gets :data:`JSON_HELP` unless the scene
gives its own help.

Exit codes (:data:`EXIT_CODES`): 0 pass, 1 a check fails, 2 invalid input
(:class:`synth.errors.InputError`: one problem per line on stderr, never a
traceback; also a bad command line), 3 passed what was checked but some
checks were not verified, 70 internal error (any other exception: one line on
stderr, ``SYNTH_DEBUG=1`` re-raises it for the traceback), 130 interrupted
(Ctrl-C), 143 terminated (SIGTERM, handled as Ctrl-C is: the scene stops
cleanly, says so, and a bulk run can be resumed). A file-system refusal
(read-only folder, full disk, a file where a folder is needed...) is the
environment's, not a bug: exit 2 naming the path (:func:`synth.io.outputs.os_problem`).

>>> _split(["--catalogs", "my", "flowchart", "case.yaml", "--json"])
(['--catalogs', 'my'], 'flowchart', ['case.yaml', '--json'])
>>> _did_you_mean("flowchat")
"unknown command 'flowchat'; did you mean 'flowchart'? (synth --help lists the commands)"
"""

from __future__ import annotations

import argparse
import difflib
import contextlib
import importlib
import os
import signal
import sys
import threading
from dataclasses import dataclass


__all__ = ["main", "SCENES", "Scene", "EXIT_CODES", "JSON_HELP", "EX_SOFTWARE", "scene_parser"]

#: EX_SOFTWARE of BSD ``sysexits.h``: an internal software error.
EX_SOFTWARE = 70

#: Exit codes of every scene (README, "Exit codes").
EXIT_CODES = {
    0: "pass: every check passed",
    1: "fail: the design fails a check (or has no feasible design)",
    2: "invalid input or command line: one line per problem (field, value, what is accepted)",
    3: "passed what was checked, but some checks were not verified (data missing)",
    EX_SOFTWARE: "internal error: a bug in synth; one line on stderr (SYNTH_DEBUG=1 shows the traceback)",
    130: "interrupted (Ctrl-C)",
    143: "terminated (SIGTERM): stopped as on Ctrl-C",
}

#: Help of a ``--json`` flag whose scene gives none.
JSON_HELP = "print one JSON object on stdout instead of the text report"


@dataclass(frozen=True)
class Scene:
    """A sub-command: the module that registers it and its one-line help."""

    module: str
    help: str


#: name -> scene, in the order ``synth --help`` lists them. The module is imported only to run the scene.
SCENES: dict[str, Scene] = {
    "demo": Scene("synth.scenes.demo", "synthesise the most standardised tensioner for the embedded default application"),
    "flowchart": Scene("synth.scenes.flowchart", "run the thesis design flowchart (steps 0-10) on a design input"),
    "design": Scene("synth.scenes.design", "optimal tensioner from the catalogs (standardisation, cost or margin)"),
    "pareto": Scene("synth.scenes.pareto", "cost against margin: the Pareto front of the catalog designs"),
    "robust": Scene("synth.scenes.robust", "production capability of a design: P(violation), Ppk, contributors, "
                                           "the verdicts resting on illustrative limits"),
    "compare": Scene("synth.scenes.compare", "compare the flowchart with a case file's thesis-tool and real values"),
    "report": Scene("synth.scenes.report",
                    "write the design report (report.html) and results workbook (results.xlsx)"),
    "cad": Scene("synth.scenes.cad", "export the 3D model (STEP, STL, pictures) of a saved design/flowchart result"),
    "template": Scene("synth.scenes.template", "write the design-input Excel template (example values: thesis case 1)"),
    "bulk": Scene("synth.scenes.bulk", "feasibility of a portfolio of applications (CSV, Excel or Parquet table)"),
    "portfolio-sample": Scene("synth.scenes.portfolio_sample",
                              "write a synthetic portfolio of N applications (for synth bulk)"),
    "rationalise": Scene("synth.scenes.rationalise",
                         "the fewest standard parts that serve a whole portfolio (platform rationalisation)"),
    "drive": Scene("synth.scenes.drive", "the belt drive around the tensioner: tensions, modes, arm response vs speed"),
    "shrink-fit": Scene("synth.scenes.shrink_fit", "crankshaft toothed-pulley shrink fit (paper Tables 1-4 and verdict)"),
    "shrink-fit-select": Scene("synth.scenes.shrink_fit",
                               "best ISO 286 fit of the crank pulley after planned re-assemblies"),
    "ui": Scene("synth.scenes.ui", "the design loop in a local web application (form, checks, graphs, 3D, portfolio)"),
}


class _VersionAction(argparse.Action):
    def __init__(self, option_strings, dest, **kw):
        super().__init__(option_strings, dest, nargs=0, help="print the synth version and the catalog hash, and exit")

    def __call__(self, parser, namespace, values, option_string=None):
        # imported here: hashing the catalogs (hashlib, pickle) would add about 7 ms to every start-up, --help too
        from synth.fingerprint import version_text
        parser._print_message(version_text(getattr(namespace, "catalogs", None) or ()) + "\n", sys.stdout)
        parser.exit(0)


class _HelpNotWritten(Exception):
    """argparse's help or usage text could not be written (argparse swallows the OSError)."""

    def __init__(self, prog: str, error: OSError):
        super().__init__(prog)
        self.prog, self.error = prog, error


class _Parser(argparse.ArgumentParser):
    """argparse, except that a help text that cannot be written (a full device) is an error, not silence."""

    def _print_message(self, message, file=None):
        if not message:
            return
        try:
            (file or sys.stderr).write(message)
            (file or sys.stderr).flush()
        except OSError as exc:
            if file is sys.stdout:
                raise _HelpNotWritten(self.prog, exc) from None


def _top_parser() -> argparse.ArgumentParser:
    width = max(len(n) for n in SCENES) + 2
    commands = "\n".join(f"  {name:<{width}}{s.help}" for name, s in SCENES.items())
    codes = "\n".join(f"  {code:<4}{text}" for code, text in EXIT_CODES.items())
    p = _Parser(
        prog="synth", usage="synth [--catalogs DIR] [--threads N] [--version] COMMAND [ARGS ...]", allow_abbrev=False,
        description="Timing-belt tensioner design synthesiser.",
        epilog=f"commands (synth COMMAND --help for the options of one):\n{commands}\n\nexit codes:\n{codes}",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--catalogs", metavar="DIR", action="append", default=[],
                   help="a folder of user catalogs overriding the built-in CSVs (repeatable)")
    p.add_argument("--threads", metavar="N", default=None,
                   help="threads synth may use for big batches (default: SYNTH_THREADS, else the processors this "
                        "process may use: affinity and CPU quota; never more); small dense algebra uses 1")
    p.add_argument("--version", action=_VersionAction)
    return p


class _SceneParser(_Parser):
    """A scene's own parser: ``--json`` gets :data:`JSON_HELP` when the scene gives no help."""

    def add_argument(self, *names, **kw):
        if "--json" in names and not kw.get("help"):
            kw["help"] = JSON_HELP
        return super().add_argument(*names, **kw)


class _Registry:
    """What a scene's ``register(sub)`` is handed: ``add_parser`` builds a stand-alone parser per scene."""

    def __init__(self):
        self.parsers: dict[str, argparse.ArgumentParser] = {}

    def add_parser(self, name: str, *, help: str | None = None, **kw) -> argparse.ArgumentParser:  # noqa: A002
        kw.setdefault("description", help)
        p = _SceneParser(prog=f"synth {name}", **kw)
        self.parsers[name] = p
        return p


def scene_parser(name: str) -> argparse.ArgumentParser:
    """The parser of scene ``name`` (imports its module)."""
    registry = _Registry()
    importlib.import_module(SCENES[name].module).register(registry)
    return registry.parsers[name]


def _did_you_mean(word: str) -> str:
    close = difflib.get_close_matches(word, list(SCENES), n=1, cutoff=0.6)
    hint = f"; did you mean '{close[0]}'?" if close else ";"
    return f"unknown command '{word}'{hint} (synth --help lists the commands)"


def _split(argv: list[str]) -> tuple[list[str], str | None, list[str]]:
    """``(top-level options, scene name, scene arguments)``: the scene is the first word that is not an option."""
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in ("--catalogs", "--threads"):
            i += 2
        elif a.startswith("-"):
            i += 1
        else:
            return argv[:i], a, argv[i + 1:]
    return argv, None, []


def _refuse_empty_values(parser: argparse.ArgumentParser, args) -> None:
    """An option or argument given an empty or blank value (``--fix ''``, ``--rules ''``, ``--cad ''``, ``synth
    design ''``) is refused naming it: argparse takes it, and a scene would read it as "not given" and silently do
    less. An option whose default is the empty text (``--author ''``) may be given it."""
    from synth.errors import InputError, Problem
    problems = []
    for action in parser._actions:
        if action.dest in ("help", "version"):
            continue
        value = getattr(args, action.dest, None)
        if value == action.default:
            continue
        values = value if isinstance(value, list) else [value]
        if any(isinstance(v, str) and not v.strip() for v in values):
            name = max(action.option_strings, key=len) if action.option_strings else (action.metavar or action.dest)
            hint = ("" if not action.option_strings else "; leave the option out for its default" if action.metavar
                    is None else f"; leave the option out for its default, or give {action.metavar}")
            problems.append(Problem(name, value if not isinstance(value, list) else " ".join(map(str, value)),
                                    f"a non-empty value{hint}"))
    if problems:
        raise InputError(problems)


def _print_input_error(exc) -> None:
    print("synth: invalid input", file=sys.stderr)
    for problem in exc.problems:
        print(f"  - {problem}", file=sys.stderr)


@contextlib.contextmanager
def _sigterm_as_interrupt():
    """SIGTERM raises :class:`synth.errors.Terminated` (a :class:`KeyboardInterrupt`) in the main thread for the
    span of a command, so it stops every scene as Ctrl-C does; the previous handler is restored after."""
    from synth.errors import Terminated
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum, frame):
        raise Terminated()
    try:
        previous = signal.signal(signal.SIGTERM, handler)
    except (ValueError, OSError):  # pragma: no cover - no signals here (an embedded interpreter)
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def main(argv: list[str] | None = None) -> int:
    """Run ``synth ARGV``; returns the exit code (:data:`EXIT_CODES`)."""
    with _sigterm_as_interrupt():
        try:
            return _main(argv)
        except _HelpNotWritten as exc:  # synth --help > /dev/full: said, not swallowed as argparse does
            from synth.errors import InputError
            _print_input_error(InputError(_stdout_problem(exc.error, exc.prog.removeprefix("synth").strip(), [],
                                                          what="help text")))
            return 2


def _main(argv: list[str] | None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    head, name, rest = _split(argv)
    top = _top_parser()
    top_args = top.parse_args(head)
    if name is None:
        top.print_help()
        return 2
    if name not in SCENES:
        top.print_usage(sys.stderr)
        print(f"synth: error: {_did_you_mean(name)}", file=sys.stderr)
        return 2
    from synth.errors import DeclarationError, InputError, Terminated
    from synth.io.outputs import FS_ERRNOS, os_problem
    from synth import threads
    pools = contextlib.ExitStack()
    try:
        pools.enter_context(threads.scene(top_args.threads))  # the scene's thread pools, before its imports load BLAS
        from synth import plugins
        plugins.load()  # the installed plug-ins' declarations, before the options that list them (--objective)
        parser = scene_parser(name)
        args = parser.parse_args(rest)
        _refuse_empty_values(parser, args)
        if top_args.catalogs:
            from synth import catalog
            catalog.set_user_dirs(*top_args.catalogs)
        code = int(args.func(args) or 0)  # the scene resolves its configuration (synth.scenes._options)
        sys.stdout.flush()  # a failed write of the output (a full disk) is reported here, not at exit unnoticed
        return code
    except BrokenPipeError:  # output piped into head & co.
        sys.stderr.close()
        return 0
    except InputError as exc:
        _print_input_error(exc)
        return 2
    except DeclarationError as exc:  # a check or plug-in declared so that it cannot be honoured: not synth's bug
        print("synth: invalid declaration", file=sys.stderr)
        print(f"  - {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:
        terminated = isinstance(exc, Terminated)
        print(f"synth {name}: {'terminated (SIGTERM)' if terminated else 'interrupted'}", file=sys.stderr)
        return 143 if terminated else 130
    except OSError as exc:
        if exc.errno not in FS_ERRNOS:
            return _internal(name, exc)
        if exc.filename:
            problem = os_problem(exc, "path", verb="use")
        else:  # no file named: the write that failed is the standard output's (synth design --json > /dev/full)
            problem = _stdout_problem(exc, name, rest)
        _print_input_error(InputError(problem))
        return 2
    except _HelpNotWritten:
        raise
    except Exception as exc:  # the one place where any error becomes a line, not a traceback
        return _internal(name, exc)
    finally:
        pools.close()


def _stdout_problem(exc: OSError, name: str, rest: list, what: str | None = None):
    """A failed write of the standard output as a Problem: which output (``--json``'s or the report's), where it
    goes (the file or device it is redirected to) and why; the output is then incomplete."""
    from synth.errors import Problem
    from synth.io.outputs import FS_ERRNOS
    try:
        target = os.readlink("/proc/self/fd/1")  # Linux: the file or device the output is redirected to
    except (OSError, ValueError):
        target = "standard output"
    where = f"{f'synth {name}'.strip()}{' --json' if '--json' in rest else ''}: standard output"
    what = what or ("JSON" if "--json" in rest else "report")
    return Problem(where, target, f"an output synth can write ({FS_ERRNOS.get(exc.errno, exc.strerror)}); the "
                                  f"{what} written there is incomplete: redirect it to a file on a device with space")


def _internal(name: str, exc: Exception) -> int:
    if os.environ.get("SYNTH_DEBUG", "") not in ("", "0"):
        raise exc
    message = " ".join(str(exc).split())[:500]
    print(f"synth: internal error in {name}: {type(exc).__name__}: {message}; please report "
          "(SYNTH_DEBUG=1 shows the traceback)", file=sys.stderr)
    return EX_SOFTWARE


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
