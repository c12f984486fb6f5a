"""``synth report INPUT --out DIR``: the design report (HTML) and the results workbook (.xlsx).

Runs the flowchart on INPUT (.yaml, .toml, .json or the Excel template) and
writes ``DIR/report.html`` (self-contained: summary, output table, every
verdict with its margin, the thesis's graphs) and ``DIR/results.xlsx``
(output table with verdict colours, checks, echo of the data read,
suggested corrections, and one sheet per other scene result given with
``--optimum``, ``--pareto``, ``--solvers``).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from synth import flowchart, schema
from synth.checks import FAIL
from synth.errors import InputError, Problem
from synth.scenes.flowchart import add_model_options, settings_from_args

__all__ = ["register", "make_report", "read_table", "out_folder"]


def register(sub) -> None:
    p = sub.add_parser("report", help="write the design report (report.html) and results workbook (results.xlsx)")
    p.add_argument("input", help="design input (.yaml, .toml, .json, or the .xlsx template)")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder")
    p.add_argument("--optimum", metavar="FILE", help="an optimum (JSON/YAML mapping or CSV) to add as a sheet")
    p.add_argument("--pareto", metavar="FILE", help="a Pareto front (CSV/JSON rows, numeric objective columns)")
    p.add_argument("--solvers", metavar="FILE", help="a solver comparison (CSV/JSON rows: solver, numbers)")
    p.add_argument("--cad", metavar="PNG", action="append", default=[], help="a CAD picture to include (repeatable)")
    add_model_options(p)
    p.set_defaults(func=_main)


def read_table(path: str | Path, option: str = "scene result file"):
    """Rows of a scene result file: CSV, JSON or YAML (a list of mappings or one mapping), through the input gate."""
    from synth.io.documents import read_rows
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


def make_report(input_path, out_dir, settings: flowchart.Settings | None = None, *, scenes: dict | None = None,
                cad: list | None = None, show_progress: bool = True) -> dict:
    """Run the flowchart on ``input_path`` and write ``report.html`` and ``results.xlsx`` into ``out_dir``.

    Returns ``{"html": Path, "xlsx": Path, "result": FlowchartResult, "graphs": [...], "skipped": [...]}``.
    """
    from synth.excel.results import write_results
    from synth.report.html import write_html
    from synth.report.plots import build_graphs

    src = Path(input_path)
    data = schema.read_mapping(src)
    cells = None
    if src.suffix.lower() in (".xlsx", ".xlsm"):
        from synth.excel.reader import read_cells
        cells = read_cells(src)[1]
    result = flowchart.run(schema.validate(data), settings or flowchart.Settings())
    scenes = {k: v for k, v in (scenes or {}).items() if v is not None}
    extra = {"pareto": scenes.get("Pareto"), "solvers": scenes.get("Solvers"), "cad": list(cad or [])}
    graphs, skipped = build_graphs(result, extra, show_progress=show_progress)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    html_path = write_html(out / "report.html", result, graphs, skipped, source=str(src), scenes=scenes)
    xlsx_path = write_results(out / "results.xlsx", result, cells=cells, source=str(src), scenes=scenes)
    return {"html": html_path, "xlsx": xlsx_path, "result": result, "graphs": graphs, "skipped": skipped}


def _main(args) -> int:
    out_folder(args.out)
    scenes = {name: read_table(path, f"--{name.lower()}") for name, path in
              (("Optimum", args.optimum), ("Pareto", args.pareto), ("Solvers", args.solvers)) if path}
    for png in args.cad:
        if not Path(png).is_file():
            raise InputError(Problem("--cad", png, "an existing PNG file"))
    r = make_report(args.input, args.out, settings_from_args(args), scenes=scenes, cad=args.cad)
    print(f"wrote {r['html']} ({len(r['graphs'])} graphs) and {r['xlsx']}")
    for s in r["skipped"]:
        print(f"  graph not drawn: {s.title}: {s.reason}", file=sys.stderr)
    return 1 if r["result"].verdict == FAIL else 0
