"""Going beyond the paper: the best ISO 286 fit for a journal, and margin versus re-assembly count.

A re-assembly is one pull-off plus one press-on: ``2 n`` displacements of
eq. (19) after ``n`` re-assemblies (the paper's case, i = 2, is one
re-assembly). The slip margin is evaluated at the fit's minimum interference
(the weakest joint the tolerances allow), after the planned re-assemblies,
against ``slip_safety x design load``. A fit is admissible when its minimum
interference is positive, its maximum interference on new surfaces (the
highest pressure ever reached) keeps the hub and the journal elastic (Lame,
von Mises; see :mod:`~synth.shrink_fit.pressure`), and its slip margin after
the planned re-assemblies is not negative (a fit that slips is never
labelled admissible): the analysis's checks (the registry's group
``shrink_fit``) with the registry's verdict rule (a margin above
``-FEAS_TOL``, round-off of equal values, passes).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from synth.design.result import FAIL, Check
from synth.shrink_fit.analysis import design_load_torque_nm, evaluate
from synth.shrink_fit.fits import candidate_fits, fit_limits
from synth.shrink_fit.inputs import ShrinkFitCase
from synth.shrink_fit.pressure import hub_yield_pressure_mpa, journal_yield_pressure_mpa
from synth.shrink_fit.torque import slip_margin
from synth.io.outputs import write_figure

__all__ = ["margin_vs_reassemblies", "select_fit", "plot_margins"]


def margin_vs_reassemblies(case: ShrinkFitCase, max_reassemblies: int = 5, fits=None) -> dict:
    """Slip margin at minimum interference for ``n = 0 .. max_reassemblies`` re-assemblies.

    ``fits``: designations (default: the case's own interference range,
    labelled by its fit or ``"input"``). Returns ``{"reassemblies": [...],
    "margins": {fit: [...]}}`` (lists of floats).
    """
    n = np.arange(int(max_reassemblies) + 1)
    load = design_load_torque_nm(case)["design_load_nm"]
    if fits is None:
        ranges = {case.fit or "input": case.interference_min_mm}
    else:
        ranges = {f: fit_limits(f)["interference_min_mm"] for f in fits}
    margins = {}
    for label, u_min in ranges.items():
        torque = evaluate(case, np.full(n.shape, u_min), 2 * n)["torque_nm"]
        margins[label] = slip_margin(torque, load, case.slip_safety).tolist()
    return {"reassemblies": n.tolist(), "margins": margins}


def select_fit(case: ShrinkFitCase, reassemblies: int = 1, hole_grade: int = 7, shaft_grade: int = 6) -> dict:
    """Best H/<shaft> fit for the case's journal after ``reassemblies`` re-assemblies.

    Returns ``fit`` (designation, or None if no candidate is admissible),
    ``margin`` (its slip margin), ``reassemblies``, ``displacements`` and
    ``rows``: per candidate ``fit, interference_min_mm, interference_max_mm,
    pressure_max_mpa, yield_pressure_mpa, slip_margin, torque_min_nm,
    admissible, reason``.
    """
    d = case.journal_outer_diameter_mm
    load = design_load_torque_nm(case)["design_load_nm"]
    p_hub = float(hub_yield_pressure_mpa(d, case.hub_outer_diameter_mm, case.hub_yield_mpa))
    p_jou = float(journal_yield_pressure_mpa(d, case.journal_inner_diameter_mm, case.journal_yield_mpa))
    p_yield = min(p_hub, p_jou)
    rows = []
    for fit in candidate_fits(d, hole_grade, shaft_grade):
        lim = fit_limits(fit)
        c = replace(case, fit=fit, interference_min_mm=lim["interference_min_mm"],
                    interference_max_mm=lim["interference_max_mm"])
        p_max = float(evaluate(c, lim["interference_max_mm"], 0)["pressure_mpa"])
        worst = evaluate(c, max(lim["interference_min_mm"], 0.0), 2 * reassemblies)
        # the analysis's checks (the registry's group "shrink_fit"), judged by the registry's verdict rule
        elastic = [Check.judged("shrink_fit_hub_elastic", p_max, p_hub),
                   Check.judged("shrink_fit_journal_elastic", p_max, p_jou)]
        slip = Check.judged("shrink_fit_slip_worn", float(worst["torque_nm"]), case.slip_safety * load)
        margin = slip.margin
        reason = ""
        if lim["interference_min_mm"] <= 0:
            reason = "transition fit: may be loose"
        elif any(x.verdict == FAIL for x in elastic):
            reason = f"plasticises at maximum interference ({p_max:.1f} > {p_yield:.1f} MPa)"
        elif slip.verdict == FAIL:
            reason = f"slips after {reassemblies} re-assemblies (margin {margin:+.3f} < 0)"
        rows.append({"fit": fit, "interference_min_mm": lim["interference_min_mm"],
                     "interference_max_mm": lim["interference_max_mm"], "pressure_max_mpa": p_max,
                     "yield_pressure_mpa": p_yield, "torque_min_nm": float(worst["torque_nm"]),
                     "slip_margin": margin, "admissible": not reason, "reason": reason})
    ok = [r for r in rows if r["admissible"]]
    best = max(ok, key=lambda r: r["slip_margin"]) if ok else None
    return {"fit": best["fit"] if best else None, "margin": best["slip_margin"] if best else None,
            "reassemblies": reassemblies, "displacements": 2 * reassemblies, "design_load_nm": load,
            "slip_safety": case.slip_safety, "rows": rows}


def plot_margins(curves: dict, path, title: str = "") -> None:
    """Save the margin-versus-re-assembly curves of :func:`margin_vs_reassemblies` to ``path`` (PNG/SVG/PDF)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MaxNLocator

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for label, m in curves["margins"].items():
        ax.plot(curves["reassemblies"], [100 * x for x in m], marker="o", label=label)
    ax.axhline(0.0, color="k", lw=0.8)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("re-assemblies (pull-off + press-on)")
    ax.set_ylabel("slip margin at minimum interference [%]")
    ax.set_title(title or "Crank pulley shrink fit: slip margin vs re-assembly count")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    write_figure(fig, path, "--plot")
