"""CAD export of a synthesised tensioner (thesis step 11, Fig. 75-76) with CadQuery.

``dimensions`` (result -> :class:`TensionerGeometry`), ``parts`` (one function
per part), ``assembly`` (named, coloured parts), ``verify`` (the registry's
step-11 geometric checks), ``export`` (STEP, STL, pictures).
:func:`export_result` chains them; :func:`summary_lines` is what the scenes print.
"""

from __future__ import annotations

from synth.cad.dimensions import TensionerGeometry, geometry_from

__all__ = ["TensionerGeometry", "geometry_from", "export_result", "summary_lines", "require_cadquery"]

#: what to install for the 3D model (the core install, ``pip install synth``, runs every other scene without it)
CAD_EXTRA = 'pip install "synth[cad]"'


def require_cadquery() -> None:
    """Raise :class:`~synth.errors.InputError` (exit 2) naming what to install when CadQuery is not importable."""
    from synth.errors import InputError, Problem
    try:
        import cadquery  # noqa: F401
    except ImportError as exc:
        raise InputError(Problem("cadquery", f"not installed ({exc})",
                                 f"{CAD_EXTRA} for the 3D model (STEP, STL, pictures); every other scene runs "
                                 "without it")) from None


def export_result(result, out_dir, inputs=None, *, stl: bool = True, pictures: bool = True, interference: bool = True,
                  application: str | None = None, what: str = "--out"):
    """Build, verify and export ``result`` into ``out_dir`` (``what``: its option, in messages); returns
    ``(model, checks, info)``. A part the CAD kernel cannot build fails the ``cad_solids`` check
    (:func:`synth.cad.assembly.build`): a verdict, never an internal error.

    ``info`` is ``{"files": [...], "timings_s": {...}}`` (build, verification, step, stl, pictures).
    ``application`` names the STEP product ``synth tensioner <application>``; by default the stem of the
    input or result file when one is given as a path, else the application type and fuel of the inputs.
    """
    import time

    require_cadquery()
    from synth.cad.assembly import build
    from synth.cad.export import export_model
    from synth.cad.verify import verify_model

    g = geometry_from(result, inputs)
    model = build(g)
    t = time.perf_counter()
    rules = result.get("rules") if isinstance(result, dict) else getattr(result, "rules", None)
    checks = verify_model(model, interference=interference, rules=rules)  # under the result's own rules
    t_verify = time.perf_counter() - t
    info = export_model(model, out_dir, checks=checks, stl=stl, pictures=pictures,
                        application=application or _application_name(result, inputs), result=result, what=what)
    info["timings_s"]["verification"] = t_verify
    return model, checks, info


def _application_name(result, inputs) -> str | None:
    """The stem of the input (or result) file, else ``<application_type> <engine_fuel>`` of the inputs."""
    import dataclasses
    from pathlib import Path
    for src in (inputs, result):
        if isinstance(src, (str, Path)):
            return Path(src).stem
    ins = inputs if inputs is not None else getattr(result, "inputs", None)
    if ins is None and isinstance(result, dict):
        ins = result.get("inputs")
    if dataclasses.is_dataclass(ins):
        ins = dataclasses.asdict(ins)
    if isinstance(ins, dict) and ins.get("application_type"):
        return " ".join(str(ins[k]) for k in ("application_type", "engine_fuel") if ins.get(k))
    return None


def summary_lines(model, checks, info) -> list[str]:
    """Human-readable summary: status, parts, checks, files, timings."""
    from synth.design.result import FAIL
    g = model.geometry
    lines = [f"CAD model: {g.layout} layout, {g.pulley_type} pulley, "
             f"{'with' if g.axial_damping else 'without'} axial damping, {g.wire_section} wire, {g.eccentric} pivot",
             f"result status: {g.status}" + ("" if g.feasible else "  (INFEASIBLE: the nearest design is exported)"),
             f"parts ({len(model.parts)}): " + ", ".join(model.parts), "geometric checks (step 11):"]
    for c in checks:
        con = c.constraint
        if c.value is None:
            lines.append(f"  [N/V ] {c.label}: {c.note}")
            continue
        mark = "FAIL" if c.verdict == FAIL else "PASS"
        lines.append(f"  [{mark}] {c.label}: {c.value:.4g} {con.sense} {c.limit:.4g} {con.unit}"
                     + (f"  -> {con.correction}" if c.verdict == FAIL and con.correction else "")
                     + (f"  ({c.note})" if c.note and c.verdict == FAIL else ""))
    lines.append("files: " + ", ".join(str(f) for f in info["files"] if "stl" not in str(f.parent.name))
                 + f" (+ {sum(1 for f in info['files'] if f.parent.name == 'stl')} STL)")
    lines.append("times [s]: " + ", ".join(f"{k} {v:.2f}" for k, v in info["timings_s"].items()))
    return lines
