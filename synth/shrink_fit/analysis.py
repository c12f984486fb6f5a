"""The shrink-fit scene's calculation: the paper's Tables 1-4, load, checks, verdict.

:func:`analyse` evaluates a :class:`~synth.shrink_fit.inputs.ShrinkFitCase`
for new surfaces (no displacement) and worn surfaces (after the case's
``assemblies`` displacements), each at minimum and maximum interference.
:func:`evaluate` is the vectorised core (arrays of interference and
displacement count) that :mod:`~synth.shrink_fit.selection` reuses.
"""

from __future__ import annotations

from dataclasses import asdict

import numpy as np

from synth.design.constraints import by_group
from synth.design.result import FAIL, PASS, Check
from synth.shrink_fit.fits import fit_limits
from synth.shrink_fit.friction import friction_coefficient
from synth.shrink_fit.inputs import ShrinkFitCase
from synth.shrink_fit.pressure import (contact_pressure_mpa, hub_yield_pressure_mpa, journal_yield_pressure_mpa,
                                       smoothing_factor, total_smoothing_mm)
from synth.shrink_fit.roughness import equivalent_surface, surface
from synth.shrink_fit.torque import friction_torque_nm, pulley_load_torque_nm, slip_margin

__all__ = ["SMOOTHING_TEXT", "surfaces", "design_load_torque_nm", "evaluate", "analyse", "format_report"]

SMOOTHING_TEXT = {
    "din7190_2001": "DIN 7190:2001, G = 0.8 (Rz_s + Rz_h) per displacement (the paper's eq. 18)",
    "din7190_2017": "DIN 7190-1:2017, G = 0.4 (Rz_s + Rz_h) per displacement",
}


def surfaces(case: ShrinkFitCase) -> dict:
    """Single surfaces and the equivalent new and worn pairs (paper Table 1, eq. 3-16)."""
    m = case.model

    def one(r):
        return surface(r.ra_um, r.rz_um, r.sm_um, r.rp_um, r.rv_um, case.t_m, m.rp_rv_from_rz, case.sm_over_ra)

    single = {"new_hub_bore": one(case.new_hub_bore), "worn_hub_bore": one(case.worn_hub_bore),
              "journal": one(case.journal)}
    return {"single": single,
            "equivalent": {"new": equivalent_surface(single["journal"], single["new_hub_bore"]),
                           "worn": equivalent_surface(single["journal"], single["worn_hub_bore"])}}


def _hardness(case: ShrinkFitCase) -> tuple[float, float]:
    softer = min(case.journal_hardness_hb, case.hub_hardness_hb)
    harder = max(case.journal_hardness_hb, case.hub_hardness_hb)
    return softer, (harder if case.model.adhesion_hardness == "harder" else softer)


def design_load_torque_nm(case: ShrinkFitCase) -> dict:
    """Load torque on the pulley: computed from the camshaft torque (load rule) and the stated ones.

    The design load is the largest of them (a stated pulley torque is never
    ignored). Returns ``rule, computed_nm, stated_nm, design_load_nm``.
    """
    lt = case.load
    computed = None
    if lt.camshaft_friction_torque_max_nm is not None:
        computed = float(pulley_load_torque_nm(lt.camshaft_friction_torque_max_nm, lt.gear_ratio, lt.camshafts,
                                               case.model.load_rule))
    values = [v for v in [computed, *lt.stated_pulley_torques_nm.values()] if v is not None]
    return {"rule": case.model.load_rule, "camshaft_friction_torque_max_nm": lt.camshaft_friction_torque_max_nm,
            "gear_ratio": lt.gear_ratio, "camshafts": lt.camshafts, "computed_nm": computed,
            "stated_nm": dict(lt.stated_pulley_torques_nm), "design_load_nm": max(values)}


def evaluate(case: ShrinkFitCase, interference_mm, displacements) -> dict:
    """Vectorised joint state for arrays of diametral interference [mm] and displacement counts.

    Surfaces are new for 0 displacements and worn otherwise; the smoothing
    follows eq. (18)-(19) with the case's smoothing rule. Returns arrays:
    ``smoothing_mm, pressure_mpa, p_over_hb, penetration_depth_um, k,
    k_extrapolated, mu_eq1, mu_eq2, saturated, mu, torque_eq1_nm,
    torque_eq2_nm, torque_nm`` (``mu``/``torque_nm``: the friction model's
    choice).
    """
    m = case.model
    u = np.asarray(interference_mm, dtype=float)
    n = np.asarray(displacements, dtype=float)
    s = surfaces(case)
    worn = n >= 1
    eq_new, eq_worn = s["equivalent"]["new"], s["equivalent"]["worn"]
    ra_eq = np.where(worn, eq_worn["ra_um"], eq_new["ra_um"])
    dk = np.where(worn, eq_worn["komalov"], eq_new["komalov"])
    g = total_smoothing_mm(n, case.journal_initial_rz_um, case.new_hub_bore.rz_um, case.journal.rz_um,
                           case.worn_hub_bore.rz_um, m.smoothing_rule)
    p = contact_pressure_mpa(u, case.journal_outer_diameter_mm, case.journal_inner_diameter_mm,
                             case.hub_outer_diameter_mm, case.young_modulus_mpa, g, m.pressure_rule)
    hb, hb_adhesion = _hardness(case)
    f = friction_coefficient(ra_eq, dk, p, hb, m.friction_model, case.tau0_mpa, case.beta, hb_adhesion)
    d, length = case.journal_outer_diameter_mm, case.bore_length_mm
    out = {"smoothing_mm": g, "pressure_mpa": p, "p_over_hb": p / hb, **f}
    out["torque_eq1_nm"] = friction_torque_nm(d, length, f["mu_eq1"], p)
    out["torque_eq2_nm"] = friction_torque_nm(d, length, f["mu_eq2"], p)
    out["torque_nm"] = friction_torque_nm(d, length, f["mu"], p)
    return out


def _f(x):
    x = np.asarray(x)
    return bool(x) if x.dtype == bool else float(x)


def analyse(case: ShrinkFitCase) -> dict:
    """Tables 1-4 of the paper for the case, the load, the checks and the verdict (JSON-ready dict)."""
    m = case.model
    s = surfaces(case)
    keys = ("ra_um", "rz_um", "sm_um", "rp_um", "rv_um", "t_m", "v", "b", "asperity_radius_um", "komalov")
    table1 = {"single": {name: {k: _f(v[k]) for k in keys} for name, v in s["single"].items()},
              "equivalent": {name: {k: _f(v[k]) for k in keys} for name, v in s["equivalent"].items()}}
    states = (("new", 0), ("worn", case.assemblies))
    levels = (("min", case.interference_min_mm), ("max", case.interference_max_mm))
    table2, table3, table4, grid = [], [], [], {}
    for state, n in states:
        r = {lvl: evaluate(case, u, n) for lvl, u in levels}
        grid[state] = r
        table2.append({"state": state, "displacements": n, "smoothing_total_mm": _f(r["min"]["smoothing_mm"]),
                       "pressure_min_mpa": _f(r["min"]["pressure_mpa"]), "p_min_over_hb": _f(r["min"]["p_over_hb"]),
                       "pressure_max_mpa": _f(r["max"]["pressure_mpa"]), "p_max_over_hb": _f(r["max"]["p_over_hb"])})
        for lvl, u in levels:
            x = r[lvl]
            table3.append({"state": state, "interference": lvl, "interference_mm": u,
                           "pressure_mpa": _f(x["pressure_mpa"]),
                           "penetration_depth_mm": _f(x["penetration_depth_um"]) * 1e-3, "k": _f(x["k"]),
                           "k_extrapolated": _f(x["k_extrapolated"]), "mu_eq1": _f(x["mu_eq1"]),
                           "mu_eq2": _f(x["mu_eq2"]), "saturated": _f(x["saturated"]), "mu": _f(x["mu"])})
            table4.append({"state": state, "interference": lvl, "pressure_mpa": _f(x["pressure_mpa"]),
                           "torque_eq1_nm": _f(x["torque_eq1_nm"]), "torque_eq2_nm": _f(x["torque_eq2_nm"]),
                           "torque_nm": _f(x["torque_nm"])})
    load = design_load_torque_nm(case)
    mh, sf = load["design_load_nm"], case.slip_safety
    p_hub = float(hub_yield_pressure_mpa(case.journal_outer_diameter_mm, case.hub_outer_diameter_mm, case.hub_yield_mpa))
    p_jou = float(journal_yield_pressure_mpa(case.journal_outer_diameter_mm, case.journal_inner_diameter_mm,
                                             case.journal_yield_mpa))
    p_peak = _f(grid["new"]["max"]["pressure_mpa"])
    mu_note = f"friction model '{m.friction_model}'"
    # the values the registry's shrink-fit checks compare (group "shrink_fit", synth.design.constraints)
    values = {"torque_new_min_nm": _f(grid["new"]["min"]["torque_nm"]),
              "torque_worn_min_nm": _f(grid["worn"]["min"]["torque_nm"]), "slip_torque_required_nm": sf * mh,
              "pressure_peak_mpa": p_peak, "hub_yield_pressure_mpa": p_hub, "journal_yield_pressure_mpa": p_jou}
    notes = {"shrink_fit_slip_new": f"{mu_note}; limit = slip safety {sf:g} x {mh:g} Nm",
             "shrink_fit_slip_worn": f"after {case.assemblies} displacements; {mu_note}; "
                                     f"{SMOOTHING_TEXT[m.smoothing_rule]}",
             "shrink_fit_hub_elastic": f"hub {case.hub_material}, Re {case.hub_yield_mpa:g} MPa",
             "shrink_fit_journal_elastic": f"journal {case.journal_material}, Re {case.journal_yield_mpa:g} MPa"}
    checks = [Check.judged(c.id, values[c.value], values[c.limit], notes.get(c.id, ""))
              for c in by_group("shrink_fit")]
    worst = grid["worn"]["min"] if case.assemblies >= 1 else grid["new"]["min"]
    margin = min(c.margin for c in checks)
    return {
        "name": case.name,
        "fit": fit_limits(case.fit) if case.fit else None,
        "interference_min_mm": case.interference_min_mm, "interference_max_mm": case.interference_max_mm,
        "assemblies": case.assemblies,
        "model": {**asdict(m), "smoothing_factor": smoothing_factor(m.smoothing_rule),
                  "smoothing": SMOOTHING_TEXT[m.smoothing_rule]},
        "hardness_hb": {"journal": case.journal_hardness_hb, "hub": case.hub_hardness_hb,
                        "softer": _hardness(case)[0], "adhesion_term": _hardness(case)[1]},
        "table1": table1, "table2": table2, "table3": table3, "table4": table4,
        "load": load,
        "slip_margin_elastic_eq1": _f(slip_margin(worst["torque_eq1_nm"], mh, sf)),
        "plasticity": {"hub_yield_pressure_mpa": p_hub, "journal_yield_pressure_mpa": p_jou,
                       "peak_pressure_mpa": p_peak},
        "checks": [c.as_dict() for c in checks],
        "verdict": PASS if all(c.verdict == PASS for c in checks) else FAIL,
        "margin": margin,
    }


def format_report(res: dict) -> str:
    """Plain-text report of :func:`analyse`'s result: the paper's Tables 1-4 and the verdict."""
    L = []
    fit = res["fit"]
    L.append(f"Shrink fit: {res['name']}")
    L.append(f"  fit {fit['designation'] if fit else '(none)'}: interference {res['interference_min_mm']:g} .. "
             f"{res['interference_max_mm']:g} mm; displacements i = {res['assemblies']}")
    mo = res["model"]
    L.append(f"  smoothing rule: {mo['smoothing']}")
    L.append(f"  pressure rule: {mo['pressure_rule']}; eq. (2) adhesion hardness: {mo['adhesion_hardness']} "
             f"({res['hardness_hb']['adhesion_term']:g} HB); load rule: {mo['load_rule']}; "
             f"friction model: {mo['friction_model']}; Rp, Rv from Rz: {mo['rp_rv_from_rz']}")
    L.append("")
    L.append("Table 1 - roughness [um] and derived parameters")
    t1 = res["table1"]
    cols = [("new bore", t1["single"]["new_hub_bore"]), ("worn bore", t1["single"]["worn_hub_bore"]),
            ("journal", t1["single"]["journal"]), ("eq. new", t1["equivalent"]["new"]),
            ("eq. worn", t1["equivalent"]["worn"])]
    L.append("  " + f"{'':<10}" + "".join(f"{c:>11}" for c, _ in cols))
    for key, lab in (("ra_um", "Ra"), ("rz_um", "Rz"), ("sm_um", "Sm"), ("rp_um", "Rp"), ("rv_um", "Rv"),
                     ("b", "b"), ("v", "v"), ("komalov", "Delta_K"), ("asperity_radius_um", "r")):
        L.append("  " + f"{lab:<10}" + "".join(f"{d[key]:>11.4g}" for _, d in cols))
    L.append("")
    L.append("Table 2 - contact pressure")
    L.append(f"  {'state':<6}{'sum G [mm]':>12}{'p_min [MPa]':>13}{'p/HB':>8}{'p_max [MPa]':>13}{'p/HB':>8}")
    for r in res["table2"]:
        L.append(f"  {r['state']:<6}{r['smoothing_total_mm']:>12.5f}{r['pressure_min_mpa']:>13.2f}"
                 f"{r['p_min_over_hb']:>8.3f}{r['pressure_max_mpa']:>13.2f}{r['p_max_over_hb']:>8.3f}")
    L.append("")
    L.append("Table 3 - penetration depth, k, friction coefficient")
    L.append(f"  {'state':<6}{'U':>4}{'p [MPa]':>10}{'h [mm]':>10}{'k':>8}{'mu (1)':>9}{'mu (2)':>9}{'regime':>10}")
    for r in res["table3"]:
        L.append(f"  {r['state']:<6}{r['interference']:>4}{r['pressure_mpa']:>10.2f}{r['penetration_depth_mm']:>10.5f}"
                 f"{r['k']:>8.3f}{'*' if r['k_extrapolated'] else ' '}{r['mu_eq1']:>8.3f}{r['mu_eq2']:>9.4f}"
                 f"{'plastic' if r['saturated'] else 'elastic':>10}")
    if any(r["k_extrapolated"] for r in res["table3"]):
        L.append("  * k extrapolated beyond the Fig. 3 points")
    L.append("")
    L.append("Table 4 - friction torque carried by the joint [Nm]")
    L.append(f"  {'state':<6}{'U':>4}{'p [MPa]':>10}{'M mu(1)':>10}{'M mu(2)':>10}{'M used':>10}")
    for r in res["table4"]:
        L.append(f"  {r['state']:<6}{r['interference']:>4}{r['pressure_mpa']:>10.2f}{r['torque_eq1_nm']:>10.2f}"
                 f"{r['torque_eq2_nm']:>10.2f}{r['torque_nm']:>10.2f}")
    ld = res["load"]
    L.append("")
    comp = f"{ld['computed_nm']:.4g} Nm from M_c,max {ld['camshaft_friction_torque_max_nm']:g} Nm, u {ld['gear_ratio']:g}" \
        if ld["computed_nm"] is not None else "not computed"
    stated = ", ".join(f"{k} {v:g}" for k, v in ld["stated_nm"].items()) or "none"
    L.append(f"Load torque on the pulley ({ld['rule']}): {comp}; stated: {stated}; design load {ld['design_load_nm']:.4g} Nm")
    L.append("")
    L.append("Checks")
    for c in res["checks"]:
        L.append(f"  [{c['verdict']:>4}] {c['label']}: {c['value']:.4g} {c['sense']} {c['limit']:.4g} {c['unit']} "
                 f"(margin {100 * c['margin']:+.1f} %; {c['note']})")
    L.append(f"  cautious (elastic eq. 1 friction) slip margin of the worst state: {100 * res['slip_margin_elastic_eq1']:+.1f} %")
    L.append(f"Verdict: {res['verdict'].upper()} (margin {100 * res['margin']:+.1f} %)")
    return "\n".join(L)
