"""Export of a :class:`~synth.cad.assembly.TensionerModel`: STEP assembly, STL per part, pictures.

* ``tensioner.step``: one STEP assembly, every part a named, coloured child
  (read back with ``cadquery.Assembly.importStep``), its header naming the
  application and carrying the key design values (:mod:`synth.cad.step`);
* ``stl/<part>.stl``: one binary STL per part (tessellation tolerance
  ``cad_helix_tolerance_mm``);
* ``exploded.png`` and ``section.png``: the thesis's Fig. 75 (parts pulled
  apart along the pivot axis, labelled) and Fig. 76 (the half of the model
  behind the plane through the pivot and bearing axes, seen square to the cut,
  cut faces hatched, legend and key dimensions), :mod:`synth.cad.pictures`;
* ``cad_report.json``: result status, geometry, design values, checks and timings.

The files are one output (:func:`synth.io.outputs.output_files`): written into a staging folder and moved into
``out_dir`` when every one is complete, so a failure (a full disk) leaves no empty or truncated file, and every
file is checked complete by its format first (OCCT's writers may fail without an error).
"""

from __future__ import annotations

import time
from pathlib import Path

from synth import catalog
from synth.cad.assembly import TensionerModel
from synth.cad.pictures import exploded_parts, exploded_picture, render_png, section_parts, section_picture
from synth.cad.step import design_values, export_step
from synth.io.outputs import json_text, output_file, output_files, output_folder, write_text

__all__ = ["export_step", "export_stl", "render_png", "exploded_parts", "section_parts", "export_model"]


def export_stl(model: TensionerModel, folder: str | Path, what: str = "--out") -> list[Path]:
    """One binary STL per part in ``folder`` (each checked complete: OCCT's writer reports a failure only by its
    return value)."""
    import errno
    folder = output_folder(folder, what, inside=True)
    tol = catalog.constant("cad_helix_tolerance_mm")
    out = []
    for name, shape in model.parts.items():
        p = folder / f"{name}.stl"
        with output_file(p, what) as tmp:
            if not shape.exportStl(str(tmp), tol, 0.2):
                raise OSError(errno.EIO, "the STL writer failed", str(p))
        out.append(p)
    return out



def export_model(model: TensionerModel, out_dir: str | Path, *, checks=None, step: bool = True, stl: bool = True,
                 pictures: bool = True, application: str | None = None, result=None, what: str = "--out") -> dict:
    """Write everything to ``out_dir`` (one output: every file or none, see the module doc); returns
    ``{"files": [...], "timings_s": {...}}`` and writes ``cad_report.json``. ``what`` names the option of
    ``out_dir`` in messages (``--out``, ``--cad``).

    ``application`` names the STEP product (``synth tensioner <application>``, default the result's label);
    ``result`` completes the design values of the STEP header (:func:`synth.cad.step.design_values`).
    """
    files, times = [], {"build": model.build_s}
    g = model.geometry
    design = design_values(model, result)
    label = f"{application or g.name} | {g.layout} layout | {g.status}" + ("" if g.feasible else " (INFEASIBLE: nearest design)")
    with output_files(out_dir, what) as out:
        if step:
            t = time.perf_counter()
            files.append(export_step(model, out / "tensioner.step", application=application, design=design))
            times["step"] = time.perf_counter() - t
        if stl:
            t = time.perf_counter()
            files += export_stl(model, out / "stl", what)
            times["stl"] = time.perf_counter() - t
        if pictures:
            t = time.perf_counter()
            files.append(exploded_picture(model, out / "exploded.png", title="exploded view | " + label))
            files.append(section_picture(model, out / "section.png", title="section through the pivot axis | " + label))
            times["pictures"] = time.perf_counter() - t
        report = {"status": g.status, "feasible": g.feasible, "application": application or g.name,
                  "design": design, "geometry": g.as_dict(), "parts": list(model.parts),
                  "not_built": dict(getattr(model, "unbuilt", {}) or {}),
                  "files": [str(f.relative_to(out)) for f in files], "timings_s": times,
                  "checks": [c.as_dict() for c in (checks or [])]}
        files.append(write_text(out / "cad_report.json", json_text(report, indent=2), what))
        files = [Path(out_dir) / f.relative_to(out) for f in files]
    return {"files": files, "timings_s": times}
