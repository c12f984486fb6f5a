"""``synth report INPUT|RESULT.json --out DIR``: the design report (HTML) and the results workbook (.xlsx).

The report shows the same design ``synth design INPUT`` finds, at the same
fidelity (the default synthesis of :mod:`synth.scenes._options`), or the
design of a saved result (the ``--json`` of any scene, re-verified through
the evaluator so its curves can be drawn), or with ``--flowchart`` the thesis
procedure's own design. Writes ``DIR/report.html`` (self-contained),
``DIR/report.pdf`` beside it (:mod:`synth.report.pdf`, unless ``--no-pdf``)
and ``DIR/results.xlsx``; the 3D model's section and exploded pictures are
built into ``DIR/cad`` and embedded unless ``--no-cad``. ``--author`` and
``--revision`` go into the document block and the title block of every
printed page; ``--platform`` adds a platform-rationalisation section.
"""

from __future__ import annotations

import sys
from pathlib import Path

from synth import flowchart
from synth.errors import InputError, Problem
from synth.scenes._options import add_design_options, add_robust_options, default_args, synthesise
from synth.scenes.design import with_cost
from synth.io.documents import read_rows
from synth.design.result import Result
from synth.report.document import reverified, write_files
from synth.report.source import is_result_file, read_source
from synth.report.text import verdict_line
from synth.scenes._options import robust_settings_from_args
from synth.scenes._options import rules_of, settings_from_args

__all__ = ["register", "make_report", "read_table", "out_folder"]


def register(sub) -> None:
    p = sub.add_parser("report", help="write the design report (report.html) and results workbook (results.xlsx)")
    p.add_argument("input", help="design input (.yaml, .toml, .json, .xlsx) or a saved result (--json of any scene)")
    p.add_argument("--out", required=True, metavar="DIR", help="folder for report.html, report.pdf and results.xlsx")
    p.add_argument("--flowchart", action="store_true", help="report the thesis procedure's design, not the synthesis")
    p.add_argument("--no-cad", action="store_true", help="do not build the 3D model pictures")
    p.add_argument("--optimum", metavar="FILE", help="an optimum (JSON/YAML mapping or CSV) to add as a sheet")
    p.add_argument("--pareto", metavar="FILE", help="a Pareto front (CSV/JSON rows, numeric objective columns)")
    p.add_argument("--solvers", metavar="FILE", help="a solver comparison (CSV/JSON rows: solver, numbers)")
    p.add_argument("--cad", metavar="PNG", action="append", default=[], help="a CAD picture to include (repeatable)")
    p.add_argument("--author", default="", help="author named in the document block and on every printed page")
    p.add_argument("--revision", default="", help="revision named in the document block and on every printed page")
    p.add_argument("--page", choices=("landscape", "portrait"), default="landscape", help="A4 orientation to print")
    p.add_argument("--no-pdf", action="store_true", help="do not write report.pdf beside report.html")
    p.add_argument("--platform", metavar="DIR", help="a rationalisation output (synth rationalise --out) to report")
    add_design_options(p)
    add_robust_options(p)
    p.set_defaults(func=_main)


def read_table(path: str | Path, option: str = "scene result file"):
    """Rows of a scene result file: CSV, JSON or YAML (a list of mappings or one mapping), through the input gate."""
    return read_rows(path, option)


def out_folder(path, option: str = "--out") -> Path:
    """``--out DIR`` checked before any work: a folder (existing or to create), not an existing file."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise InputError(Problem(option, str(path), "a folder (this is an existing file; give a folder name)"))
    parent = next((q for q in [p, *p.parents] if q.exists()), None)
    if parent is not None and not parent.is_dir():
        raise InputError(Problem(option, str(path), f"a folder ({parent} is a file)"))
    return p


def result_for_report(source, args=None):
    """``(result, cells, source name)`` of an input file, a saved result file or a :class:`Result`
    (:func:`synth.report.source.read_source`): an input synthesised as ``synth design`` does with the options of
    ``args`` (with its price lines), or with ``--flowchart`` by the thesis procedure (reported as it is)."""
    if args is not None and getattr(args, "flowchart", False) and not isinstance(source, Result) \
            and not is_result_file(Path(source)):
        return read_source(source, lambda d: flowchart.run(d, settings_from_args(args)))
    res, cells, name = read_source(source, lambda d: with_cost(d, args or default_args(), synthesise))
    return reverified(res, rules_of(args) if args is not None else None, name), cells, name  # --rules: a result's


def make_report(source, out_dir, args=None, *, scenes: dict | None = None, cad: list | None = None,
                show_progress: bool = True, cad_pictures: bool = True, pdf: bool = True, author: str = "",
                revision: str = "", page: str = "landscape", platform=None, source_name: str | None = None,
                application: str | None = None, robust=None, graphs: tuple | None = None) -> dict:
    """Write ``report.html``, ``report.pdf`` and ``results.xlsx`` of ``source`` (input file, saved result or Result).

    ``source_name``: the input file a given :class:`Result` was made from (the document block names it and its
    SHA-256); ``application``: the application's name, in the title and the document block; ``cad``: pictures of
    a model already exported (the report then builds none: one STEP file per run). ``robust`` (a
    :class:`synth.robust.settings.RobustSettings`): add the production-scatter section (the design's capability,
    unless the result carries it, and the verdicts resting on illustrative limits) and the ``Capability`` and
    ``Assumptions`` sheets.

    ``graphs``: ``(graphs, skipped)`` of ``source`` already drawn (:func:`~synth.report.plots.build_graphs` without
    ``extra``, as ``synth ui`` keeps them); the pictures of ``cad`` are added to them.

    Returns ``{"html": Path, "pdf": Path | None, "pdf_note": str, "xlsx": Path, "result": Result,
    "graphs": [...], "skipped": [...]}`` (``pdf_note``: why no PDF was written, when none was).
    """
    result, cells, name = result_for_report(source, args)
    return write_files(result, out_dir, cells=cells, name=str(source_name) if source_name else name, scenes=scenes,
                       cad=cad, show_progress=show_progress, cad_pictures=cad_pictures, pdf=pdf, author=author,
                       revision=revision, page=page, platform=platform, application=application, robust=robust,
                       graphs=graphs)


def _main(args) -> int:
    out_folder(args.out)
    scenes = {name: read_table(path, f"--{name.lower()}") for name, path in
              (("Optimum", args.optimum), ("Pareto", args.pareto), ("Solvers", args.solvers)) if path}
    for png in args.cad:
        if not Path(png).is_file():
            raise InputError(Problem("--cad", png, "an existing PNG file"))
    if args.platform and not Path(args.platform).exists():
        raise InputError(Problem("--platform", args.platform, "an existing rationalisation output (synth rationalise --out)"))
    rs = robust_settings_from_args(args)  # --capability/--ppm, else the design rules' capability targets
    if rs.capability is None and rs.ppm is None:
        rs = None
    r = make_report(args.input, args.out, args, scenes=scenes, cad=args.cad, cad_pictures=not args.no_cad,
                    pdf=not args.no_pdf, author=args.author, revision=args.revision, page=args.page,
                    platform=Path(args.platform) if args.platform else None, robust=rs)
    pdf = f", {r['pdf']}" if r["pdf"] else ""
    print(f"wrote {r['html']} ({len(r['graphs'])} graphs){pdf} and {r['xlsx']}")
    if not args.no_pdf and r["pdf"] is None:
        print(f"  PDF not written: {r['pdf_note']}", file=sys.stderr)
    for s in r["skipped"]:
        print(f"  graph not drawn: {s.title}: {s.reason}", file=sys.stderr)
    print(verdict_line(r["result"]))
    return r["result"].exit_code
