"""What the worker processes of ``synth ui`` run (:mod:`synth.ui.worker`): every function here is a task.

Each is a call of synth's public API or of the module a scene calls, and keeps what it built for the next task of
its process:

* the **CAD model** by the design's hash (:func:`model_key`: the geometry the model is built from, every dimension
  and part of :class:`~synth.cad.dimensions.TensionerGeometry` but its labels): built once per design, whatever the
  edits that leave the geometry as it is (the support's strength, a safety factor; a stiffness changes the spring's
  coils); its STL files, geometric checks and pictures once per model, the STEP once per model and header;
* the **graphs** of a result by the result's hash (:func:`result_key`: its pickled bytes, so every input, part,
  rule, setting, curve and capability study it holds; an edit and back finds them again), shared by the Graphs
  tab and the report;
* the **report** by what it is made from (the result's hash, the source's name, the 3D pictures), and its PDF
  by the document's hash (:func:`report`: the SHA-256 of the self-contained HTML, which embeds
  every graph and picture, with its date taken out): a second download of the same document is the first one's
  file; anything that changes a line of the report (an input, a rule, a setting, a catalog value the result
  carries, the application's name) changes the hash and prints it anew.

Nothing is imported at this module's import: a task imports what it needs, and :func:`warm` imports it ahead.

>>> echo([1, "a"])
[1, 'a']
"""

from __future__ import annotations

import collections
import copy
import dataclasses
import hashlib
import pickle
import time
from pathlib import Path

__all__ = ["echo", "warm", "open_input", "synthesise", "launch_on_disk", "model_key", "result_key", "model", "pictures", "model_details", "step", "graphs",
           "report", "capability"]

#: models, graph sets and geometric checks kept per process (least recently used dropped first)
KEEP = 8

#: the fields of a geometry that label it (its name, status and verdict): they change no solid
LABEL_FIELDS = ("name", "status", "feasible", "verdict")

_MODELS: collections.OrderedDict = collections.OrderedDict()   # model key -> TensionerModel
_CHECKS: collections.OrderedDict = collections.OrderedDict()   # model key -> [check dicts]
_GRAPHS: collections.OrderedDict = collections.OrderedDict()   # result key -> (graphs, skipped)
_DOCS: collections.OrderedDict = collections.OrderedDict()     # what a report is made from -> its files
_PDFS: collections.OrderedDict = collections.OrderedDict()     # document key -> {"pdf", "date"} of its first print


def _keep(cache: collections.OrderedDict, key, value):
    cache[key] = value
    cache.move_to_end(key)
    while len(cache) > KEEP:
        cache.popitem(last=False)
    return value


def _hash(*parts) -> str:
    return hashlib.sha256(repr(parts).encode("utf-8")).hexdigest()[:20]


def echo(x):
    """``x`` back (the worker's own test)."""
    return x


def warm(lane: str) -> float:
    """Import what lane ``lane``'s tasks need (``cad``: CadQuery and the CAD modules; ``design``: the report's
    modules, matplotlib); returns the seconds it took."""
    t = time.perf_counter()
    if lane == "cad":
        try:
            import cadquery  # noqa: F401

            import synth.cad.assembly  # noqa: F401
            import synth.cad.export  # noqa: F401
            import synth.cad.pictures  # noqa: F401
            import synth.cad.verify  # noqa: F401
        except ImportError:  # no CadQuery: the 3D tab says what to install when asked
            pass
    else:
        import matplotlib
        matplotlib.use("Agg")
        import synth.report.plots  # noqa: F401
        import synth.report.document  # noqa: F401
    return time.perf_counter() - t


# --- the launch ---------------------------------------------------------------------------------------------------
def open_input(values: dict, source: str, rules=None, catalogs=()) -> dict:
    """What the design page ``synth ui`` opens needs before its checks (:class:`synth.ui.launch.Launch`): the state
    of a design session opened on ``values`` under ``rules`` with the user catalog folders ``catalogs`` (the
    server's), the same validation as the page's (:meth:`synth.ui.session.DesignSession.opened_state`), and the
    designations its drop-downs list and its hints (:func:`synth.ui.form.catalog_texts`): ``{"opened", "keys"}``."""
    from synth import catalog
    from synth.ui import form
    from synth.ui.session import DesignSession
    from synth.ui.trace import mark
    mark("launch task: opening the input")

    def build():
        with catalog.using(list(catalogs)):
            s = DesignSession(values, source=source, rules=rules)
            return {"opened": s.opened_state(), "keys": form.catalog_texts()}
    out = _launch_cached(LAUNCH_TASKS[0], (values, source, rules, catalogs), build)
    mark("launch task: the input opened")
    return out


def synthesise(values: dict, source: str, rules=None, catalogs=()) -> tuple:
    """``(call, result)``: the synthesis of the design session :func:`open_input` opens, as the page would make it
    (:meth:`synth.ui.session.DesignSession.synthesise`); ``call`` its
    :meth:`~synth.ui.session.DesignSession.synthesis_call`, for the page to check it asks the same; ``(None, None)``
    for an input that is not valid."""
    from synth import catalog
    from synth.ui.session import DesignSession
    from synth.ui.trace import mark
    def build():
        with catalog.using(list(catalogs)):
            s = DesignSession(values, source=source, rules=rules)
            if s.input is None:
                return None, None
            return s.synthesis_call(), s.synthesise()
    out = _launch_cached(LAUNCH_TASKS[1], (values, source, rules, catalogs), build)
    mark("launch task: synthesised")
    return out


#: the names the launch tasks keep their answers under (:func:`_launch_cached`)
LAUNCH_TASKS = ("ui-launch-open", "ui-launch-synthesis")


def _launch_cached(name: str, args: tuple, build):
    """``build()`` of a launch task, kept on disk (:func:`synth.fingerprint.cached`) under its arguments, synth's
    version and source (:func:`~synth.fingerprint.source_stamp`), the catalogs' bytes (built-in and the user folders
    given) and the interpreter's and numerical libraries' versions: a second ``synth ui`` on the same input reads the
    first one's answer instead of validating and synthesising again (about 2 s of CPU). Built without the cache when
    a plug-in is installed (its code is not in the key) or the arguments cannot be pickled."""
    from synth import fingerprint
    key = _launch_key(args)
    return build() if key is None else fingerprint.cached(name, key, build)


def launch_on_disk(values: dict, source: str, rules=None, catalogs=()) -> bool:
    """Whether both launch tasks (:func:`open_input`, :func:`synthesise`) of these arguments have their answers on
    disk (:func:`_launch_cached`): reading them is a fraction of a second, no worker process needed for it."""
    from synth import fingerprint
    key = _launch_key((values, source, rules, catalogs))
    if key is None:
        return False
    paths = [fingerprint.cache_path(name, key) for name in LAUNCH_TASKS]
    return all(p is not None and p.is_file() for p in paths)


def _launch_key(args: tuple) -> list | None:
    """The key parts of a launch task's answer (:func:`_launch_cached`); None when it is not to be kept."""
    import sys
    from importlib import metadata

    from synth import fingerprint, plugins
    if plugins.load():
        return None
    try:
        call = hashlib.sha256(pickle.dumps(args, protocol=pickle.HIGHEST_PROTOCOL)).hexdigest()
    except Exception:  # noqa: BLE001 - an argument that does not pickle: no key, no cache
        return None
    libs = []
    for lib in ("numpy", "scipy", "pandas", "numba"):
        try:
            libs.append(f"{lib}={metadata.version(lib)}")
        except metadata.PackageNotFoundError:
            libs.append(f"{lib}=none")
    return [fingerprint.source_stamp(), fingerprint.catalogs_sha256(args[-1]), sys.version, *libs, call]


# --- the CAD lane --------------------------------------------------------------------------------------------------
def model_key(geometry) -> str:
    """The design's hash: every field of the geometry but its labels (:data:`LABEL_FIELDS`).

    >>> from synth.cad.dimensions import geometry_from, _example_values, _example_inputs
    >>> g = geometry_from(_example_values(), inputs=_example_inputs())
    >>> model_key(g) == model_key(dataclasses.replace(g, status="verified")), len(model_key(g))
    (True, 20)
    >>> model_key(g) == model_key(dataclasses.replace(g, pulley_diameter_mm=g.pulley_diameter_mm + 1))
    False
    """
    return _hash(*((f.name, getattr(geometry, f.name)) for f in dataclasses.fields(geometry)
                   if f.name not in LABEL_FIELDS))


def _model(result):
    """``(model with this result's labels, key, seconds built)``: the model of the result's geometry, built once."""
    from synth.cad import geometry_from, require_cadquery
    require_cadquery()
    from synth.cad.assembly import build
    g = geometry_from(result)
    key = model_key(g)
    t = time.perf_counter()
    m = _MODELS.get(key)
    if m is None:
        m = _keep(_MODELS, key, build(g))
    else:
        _MODELS.move_to_end(key)
    return dataclasses.replace(m, geometry=g), key, time.perf_counter() - t


def _bbox(model) -> list[float]:
    box = None
    for shape in model.parts.values():
        b = shape.BoundingBox()
        box = b if box is None else box.add(b)
    return [0.0] * 6 if box is None else [box.xmin, box.ymin, box.zmin, box.xmax, box.ymax, box.zmax]


def model(result, root: str) -> dict:
    """The 3D view's files of ``result``'s design, under ``root/cad/KEY``: one STL per part, its colour (RGBA,
    ``catalogs/cad_colours.csv``) and the assembly's bounding box (mm). ``{"key", "folder", "stl": {part: path},
    "colours": {part: [r, g, b, a]}, "bbox": [xmin, ymin, zmin, xmax, ymax, zmax], "timings_s": {"build", "stl"}}``."""
    from synth.cad.export import export_stl
    m, key, build_s = _model(result)
    folder = Path(root) / "cad" / key
    stl = folder / "stl"
    t = time.perf_counter()
    if not all((stl / f"{name}.stl").is_file() for name in m.parts):
        export_stl(m, stl)
    from synth.cad.assembly import colour_of
    return {"key": key, "folder": str(folder), "stl": {name: str(stl / f"{name}.stl") for name in m.parts},
            "colours": {name: list(colour_of(name)) for name in m.parts},
            "bbox": _bbox(m), "timings_s": {"build": build_s, "stl": time.perf_counter() - t}}


def pictures(result, root: str) -> dict:
    """The section and exploded pictures of ``result``'s design (what the report shows; no geometric check), once per
    model and label: ``{"key", "section", "exploded", "timings_s"}``."""
    from synth.cad.export import exploded_picture, section_picture
    m, key, build_s = _model(result)
    g = m.geometry
    label = f"{g.name} | {g.layout} layout | {g.status}" + ("" if g.feasible else " (INFEASIBLE: nearest design)")
    folder = Path(root) / "cad" / key / ("pictures-" + _hash(label))
    t = time.perf_counter()
    section, exploded = folder / "section.png", folder / "exploded.png"
    if not (section.is_file() and exploded.is_file()):
        folder.mkdir(parents=True, exist_ok=True)
        exploded_picture(m, exploded, title="exploded view | " + label)
        section_picture(m, section, title="section through the pivot axis | " + label)
    return {"key": key, "section": str(section), "exploded": str(exploded),
            "timings_s": {"build": build_s, "pictures": time.perf_counter() - t}}


def model_details(result, root: str) -> dict:
    """The step-11 geometric checks (interference included) and the pictures (:func:`pictures`) of ``result``'s
    design: ``{"key", "checks": [{"id", "label", "verdict", "note"}], "section", "exploded", "timings_s"}``."""
    from synth.cad.verify import verify_model
    m, key, _ = _model(result)
    t = time.perf_counter()
    checks = _CHECKS.get(key)
    if checks is None:
        checks = _keep(_CHECKS, key, [{"id": c.id, "label": c.label, "verdict": c.verdict, "note": c.note}
                                      for c in verify_model(m, interference=True)])
    verification_s = time.perf_counter() - t
    pics = pictures(result, root)
    return {**pics, "checks": checks, "timings_s": {"verification": verification_s,
                                                     "pictures": pics["timings_s"]["pictures"]}}


def step(result, root: str, application: str | None = None) -> dict:
    """The STEP assembly of ``result``'s design (its header: the application, the design values, the status), once
    per model and header: ``{"path", "timings_s"}``."""
    from synth.cad.step import design_values, export_step
    m, key, build_s = _model(result)
    design = design_values(m, result)
    g = m.geometry
    folder = Path(root) / "cad" / key / ("step-" + _hash(application, sorted(design.items()), g.name, g.status,
                                                          g.verdict, g.feasible))
    path = folder / "tensioner.step"
    t = time.perf_counter()
    if not path.is_file():
        folder.mkdir(parents=True, exist_ok=True)
        export_step(m, path, application=application, design=design)
    return {"path": str(path), "timings_s": {"build": build_s, "step": time.perf_counter() - t}}


# --- the design lane -----------------------------------------------------------------------------------------------
def result_key(result) -> str:
    """The result's hash: the SHA-256 of its pickled bytes (every input, part, rule, setting, check, curve and
    capability record it holds). Two results with the same bytes draw the same graphs; two that differ in anything
    have different keys (a result made another way that happens to be equal may miss: a cost, never a wrong answer).

    >>> from synth.design.result import Check, Result
    >>> a = Result("verified", parts={"ball_bearing": "6006"}, checks=[Check("bearing_load", 462.5, 900.0, 0.49, "pass")])
    >>> b = Result("verified", parts={"ball_bearing": "6006"}, checks=[Check("bearing_load", 462.5, 910.0, 0.49, "pass")])
    >>> result_key(a) == result_key(copy.deepcopy(a)), result_key(a) == result_key(b)
    (True, False)
    """
    return hashlib.sha256(pickle.dumps(result, protocol=pickle.HIGHEST_PROTOCOL)).hexdigest()[:24]


def graphs(result):
    """``(graphs, skipped)`` of ``result`` (:func:`synth.report.plots.build_graphs`, the report's), drawn once per
    result (:func:`result_key`)."""
    key = result_key(result)
    hit = _GRAPHS.get(key)
    if hit is not None:
        _GRAPHS.move_to_end(key)
        return hit
    import matplotlib
    matplotlib.use("Agg")
    from synth.report.plots import build_graphs
    return _keep(_GRAPHS, key, build_graphs(result, show_progress=False))


def document_key(html_text: str, date: str) -> str:
    """The report's hash: its self-contained HTML (every graph and picture embedded) with its date taken out.

    >>> document_key("<p>2030-01-01 10:00 UTC</p><p>x</p>", "2030-01-01 10:00 UTC") == \\
    ...     document_key("<p>2030-01-01 10:01 UTC</p><p>x</p>", "2030-01-01 10:01 UTC")
    True
    """
    return hashlib.sha256(html_text.replace(date, "").encode("utf-8")).hexdigest()[:24]


def _made_from(result, source: str, pictures: tuple) -> str:
    """What a report is made from: the result (:func:`result_key`), the source's name and the file it names (the
    document block shows its SHA-256), and the 3D pictures' bytes."""
    from synth.fingerprint import file_sha256
    src = Path(source) if source else None
    return _hash(result_key(result), source, file_sha256(src) if src is not None and src.is_file() else "",
                 *(hashlib.sha256(Path(p).read_bytes()).hexdigest() for p in pictures))


def report(result, folder: str, *, pdf: bool, source: str = "", pictures: tuple = (),
           root: str | None = None) -> dict:
    """The report of ``result`` into ``folder`` (``synth report``'s HTML and results workbook, with the graphs of
    :func:`graphs` and the 3D model's ``pictures``), and with ``pdf`` its PDF (:func:`synth.ui.printer.print_pdf`):
    ``{"html", "xlsx", "pdf", "pdf_note", "document", "printed", "timings_s"}``.

    Made once per result, source and pictures (:func:`_made_from`: the files of an earlier call into the same folder
    are returned, those of a call into another folder (another tab's) copied into this one), and
    printed once per document (:func:`document_key`: the PDF of a document printed before is that print, and its
    HTML the one it was printed from, dated when it was first made); ``printed`` says whether this call printed."""
    import shutil
    t0 = time.perf_counter()
    pictures = tuple(p for p in pictures if Path(p).is_file())
    made_from = _made_from(result, source, pictures)
    key = (made_from, str(Path(folder).resolve()))  # a page's files are in its own folder, never another tab's
    made = _DOCS.get(key)
    if made is not None and _written(made):
        _DOCS.move_to_end(key)
    else:
        other = next((m for (f, _), m in reversed(_DOCS.items()) if f == made_from and _written(m)), None)
        made = _keep(_DOCS, key, _copied(other, folder) if other is not None
                     else _write_report(result, folder, source, pictures))
    t1 = time.perf_counter()
    files = {"html": made["html"], "xlsx": made["xlsx"], "pdf": None, "pdf_note": "not asked for",
             "document": made["document"], "printed": False}
    if pdf:
        doc, html_path = made["document"], Path(made["html"])
        path = html_path.with_suffix(".pdf")
        hit = _PDFS.get(doc)
        if hit is not None and Path(hit["pdf"]).is_file():
            _PDFS.move_to_end(doc)
            if not path.is_file():
                shutil.copyfile(hit["pdf"], path)
            files["pdf"], files["pdf_note"] = str(path), ""
        else:
            from synth.ui.printer import print_pdf
            printed, _, note = print_pdf(html_path, folder=root)
            files["pdf"], files["pdf_note"], files["printed"] = (str(printed) if printed else None), note, True
            if printed:  # a copy of its own: the folder it was printed in may be written again
                kept = Path(root or html_path.parent) / "documents" / f"{doc}.pdf"
                kept.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(printed, kept)
                _keep(_PDFS, doc, {"pdf": str(kept), "date": made["date"]})
    files["timings_s"] = {"html_and_workbook": t1 - t0, "pdf": time.perf_counter() - t1}
    return files


def _written(made: dict) -> bool:
    return all(Path(made[k]).is_file() for k in ("html", "xlsx"))


def _copied(made: dict, folder: str) -> dict:
    """The files of a report made for another folder (another tab's), copied into ``folder``: the same document."""
    import shutil
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    return {**made, **{k: str(shutil.copyfile(made[k], out / Path(made[k]).name)) for k in ("html", "xlsx")}}


def _write_report(result, folder: str, source: str, pictures: tuple) -> dict:
    """Write the HTML and the workbook: ``{"html", "xlsx", "document", "date"}``; a document printed before keeps
    the date it was printed with (its HTML then is the one printed)."""
    from synth.report.document import reverified, write_files
    from synth.report.html import document_date
    drawn = graphs(result)
    date = document_date()
    out = write_files(reverified(result), folder, cad=list(pictures), graphs=drawn, pdf=False, show_progress=False,
                      cad_pictures=False, name=source or "result", date=date)
    html_path = Path(out["html"])
    text = html_path.read_text(encoding="utf-8")
    doc = document_key(text, date)
    hit = _PDFS.get(doc)
    if hit is not None and hit["date"] != date:  # the HTML as it was printed: the same document, dated as its PDF
        html_path.write_text(text.replace(date, hit["date"]), encoding="utf-8")
        date = hit["date"]
    return {"html": str(html_path), "xlsx": str(out["xlsx"]), "document": doc, "date": date}


def capability(result, target: float | None, ppm: float | None):
    """``synth.capability`` of ``result``'s design for a Ppk ``target`` and a ``ppm`` limit: its ``robust`` record."""
    import synth
    r = copy.deepcopy(result)
    r.robust = {}  # studied anew for this target
    return synth.capability(r, target=target, ppm=ppm).robust
