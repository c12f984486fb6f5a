"""The design report's files of a :class:`~synth.design.result.Result`: ``report.html``, ``report.pdf`` and
``results.xlsx`` (and the 3D model's pictures in ``cad/``), as ``synth report`` writes them.

The scene (:mod:`synth.scenes.report`) reads what the user names (an input file, a saved result) into a result;
the Python API (:func:`synth.write_report`) and the web UI (:mod:`synth.ui.work`) hand a result here directly.
"""

from __future__ import annotations

from pathlib import Path

from synth import schema
from synth.design.result import Result
from synth.design.settings import Settings
from synth.design.verify import verify
from synth.errors import InputError, Problem
from synth.io.outputs import output_files, refuse_link
from synth.io.saved_results import INPUTS_ACCEPTED
from synth.report.html import write_html
from synth.report.pdf import write_pdf
from synth.report.plots import build_graphs, cad_graphs
from synth.report.robust import capability_rows
from synth.robust.capability import add_capability

__all__ = ["reverified", "write_files"]


def reverified(res: Result, given=None, name: str = "result") -> Result:
    """``res`` ready for its report: its inputs required (the report echoes them), and a design without its curves
    verified again through the evaluator for the curves of the graphs, under its own configuration (``given``:
    the design rules, :class:`~synth.design.rules.Rules`, of a result that carries none)."""
    if res.inputs is None:
        raise InputError(Problem(f"inputs ({Path(name).name})", None, INPUTS_ACCEPTED))
    if not res.curves and res.parts and res.solver != "flowchart":  # re-verify for the curves of the graphs
        settings = Settings.from_saved(res.settings, res.rules or (given.as_dict() if given and not given.empty()
                                                                   else None))  # the result's own configuration
        again = verify(schema.validate({k: v for k, v in res.inputs.items() if v is not None}), res.parts, settings,
                       status=res.status, solver=res.solver, time_points=60, notes=res.notes)
        res = again.carry(res)
    return res


def write_files(result: Result, out_dir, *, cells=None, name: str = "result", scenes: dict | None = None,
                cad: list | None = None, show_progress: bool = True, cad_pictures: bool = True, pdf: bool = True,
                author: str = "", revision: str = "", page: str = "landscape", platform=None,
                application: str | None = None, robust=None, graphs: tuple | None = None,
                date: str | None = None) -> dict:
    """Write ``report.html``, ``report.pdf`` and ``results.xlsx`` of ``result`` (:func:`reverified`) into
    ``out_dir``: the keywords are :func:`synth.scenes.report.make_report`'s, ``cells`` the input workbook's cells
    (echoed), ``name`` the source's name (the document block names it and its SHA-256) and ``date`` the document's
    date (default: now, :func:`synth.report.html.document_date`)."""
    from synth.excel.results_workbook import write_results
    if robust is not None and result.parts:
        add_capability(result, robust)
    if cad_pictures and not cad:
        refuse_link(Path(out_dir) / "cad", "--out")  # before the work: never through a link the folder holds
    with output_files(out_dir, "--out") as out:  # one output: every file, or none (a full disk)
        final = Path(out_dir)
        pictures = list(cad or [])
        cad_note = (f"The model of this design: {Path(pictures[0]).parent} (STEP assembly and pictures)." if pictures
                    else "")
        if cad_pictures and not pictures and result.parts:
            try:
                from synth.cad import export_result
                _, _, info = export_result(result, out / "cad", stl=False, pictures=True, interference=False)
                pictures = [str(f) for f in info["files"] if str(f).endswith(".png")]
                cad_note = f"The model of this design: {final / 'cad'} (STEP assembly and pictures)."
            except InputError as exc:  # a design the CAD model cannot draw: the report says so
                cad_note = f"3D model not drawn: {exc}"
                result.notes.append(cad_note)
        scenes = {k: v for k, v in (scenes or {}).items() if v is not None}
        extra = {"pareto": scenes.get("Pareto"), "solvers": scenes.get("Solvers"), "cad": pictures}
        if graphs is None:
            graphs, skipped = build_graphs(result, extra, show_progress=show_progress)
        else:
            graphs, skipped = [*graphs[0], *cad_graphs(pictures)], list(graphs[1])
        html_path = write_html(out / "report.html", result, graphs, skipped, source=name, scenes=scenes,
                               author=author, revision=revision, page=page, platform=platform, cad_note=cad_note,
                               application=application, date=date)
        pdf_path, pdf_note = None, "not asked for"
        if pdf:
            pdf_path, _, pdf_note = write_pdf(html_path)
        sheets = dict(scenes)
        if result.robust.get("checks"):
            sheets["Capability"] = capability_rows(result.robust)
        if result.robust.get("assumptions"):
            sheets["Assumptions"] = [{"assumption": a["id"], "catalog": a["catalog"], "key": a["key"],
                                      "column": a["column"], "value": str(a["value"]), "low": a["low"], "high": a["high"],
                                      "scale": a["scale"], "flips": "; ".join(f"{f['check']}: {f['nominal']} -> "
                                                                              f"{f['at_low']} / {f['at_high']}"
                                                                              for f in a["flips"]),
                                      "reason": a["reason"], "source": a["source"]} for a in result.robust["assumptions"]]
        xlsx_path = write_results(out / "results.xlsx", result, cells=cells, source=name, scenes=sheets)
        html_path, xlsx_path = final / html_path.relative_to(out), final / xlsx_path.relative_to(out)
        pdf_path = None if pdf_path is None else final / pdf_path.relative_to(out)
    return {"html": html_path, "pdf": pdf_path, "pdf_note": pdf_note if pdf_path is None else "", "xlsx": xlsx_path,
            "result": result, "graphs": graphs, "skipped": skipped}
