"""Synthetic feasibility data shaped like a real portfolio (tests and benchmarks).

The producer of real feasibility data is the vectorised evaluator run over a portfolio;
this module makes data of the same shape and structure without it, so the platform
model can be tested against brute force and timed at 1,000 applications. The numbers
are **illustrative** (not catalog data): a plausible engineering skeleton whose
feasible sets have the real data's structure -- nested capacities (a bigger bearing,
a longer bushing, a stronger bolt serve more), windows (a main spring's coil count must
fit the application's stiffness, its diameters the housing of the core), and groups
(cores share a spring group when they give the same spring torque and housing).

Shape (defaults): 16 bearings, 20 pivot classes, 3 bushing suppliers x 8 lengths,
5 damper pads (+ none), 5 endcap spacers x 3 cone-spring variants (+ the no-axial
option), 4 materials x 50 wires x 15 mean body diameters = 3,000 main springs, 8 bolt
formats x 5 property classes = 40 bolts.

>>> pf = synthetic_portfolio(4, seed=1)
>>> len(pf.apps), pf.n_options("spring"), pf.n_options("bolt"), sorted(pf.option_cost_eur)
(4, 3000, 40, ['axial', 'bolt', 'bushing', 'spring'])
"""

from __future__ import annotations

import numpy as np

from synth.platform.data import (AppFeasibility, PortfolioFeasibility,
                                 default_fixed_costs)

__all__ = ["synthetic_portfolio", "SHAPE"]

#: default sizes of the part families
SHAPE = dict(bearings=16, pivots=20, suppliers=3, lengths=8, pads=5, spacers=5, cones=3,
             materials=4, wires=50, mbds=15, bolt_formats=8, bolt_classes=5)


def _groups(keys: np.ndarray):
    """Group id per row of ``keys`` and the first row of each group."""
    uniq, first, inv = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return np.asarray(inv).reshape(-1), first


def synthetic_portfolio(n_apps: int, seed: int = 0, **shape) -> PortfolioFeasibility:
    """``n_apps`` applications of synthetic feasibility data (sizes: :data:`SHAPE`, overridable)."""
    sh = {**SHAPE, **shape}
    rng = np.random.default_rng(seed)
    nb, npv, ns, nl, npd = sh["bearings"], sh["pivots"], sh["suppliers"], sh["lengths"], sh["pads"]
    # ---- parts ------------------------------------------------------------------------------
    bear_D = np.round(np.linspace(30, 62, nb) + rng.uniform(-1, 1, nb), 1)
    bear_cap = 2.2 * bear_D ** 2 * rng.uniform(0.85, 1.15, nb)            # N, max hubload
    bear_cost = 0.8 + 0.05 * bear_D
    piv_d = np.arange(npv) + 8.0                                            # mm
    sup_t = np.linspace(1.0, 2.0, ns)                                       # wall thickness, mm
    sup_pmax = np.linspace(12.0, 20.0, ns)[rng.permutation(ns)]              # MPa
    lengths = np.linspace(6.0, 20.0, nl)
    pad_cap = np.linspace(1.5, 6.0, npd) * rng.uniform(0.9, 1.1, npd)       # Nm axial damping
    pad_h = np.linspace(3.0, 7.0, npd)
    pad_cost = 0.3 + 0.1 * np.arange(npd)
    spa_cap = np.linspace(2.0, 7.0, sh["spacers"])
    cone_lo = np.linspace(60.0, 700.0, sh["cones"])                        # N, force band per variant
    cone_hi = cone_lo * 3.5
    mat_sig = np.linspace(1400.0, 2000.0, sh["materials"]) * rng.uniform(0.97, 1.03, sh["materials"])
    mat_E = rng.choice([196e3, 200e3, 206e3], sh["materials"])
    mat_cost = np.linspace(1.0, 1.6, sh["materials"])
    wire_d = np.round(np.linspace(2.5, 7.0, sh["wires"]), 3)
    mbd = np.linspace(20.0, 62.0, sh["mbds"])
    bolt_d = np.linspace(6.0, 14.0, sh["bolt_formats"])
    cls_f = np.linspace(0.6, 1.2, sh["bolt_classes"])
    # ---- global option tables ---------------------------------------------------------------
    parts = {"ball_bearing": [f"B{int(D * 10):04d}" for D in bear_D],
             "pivot_class_diameter_mm": [f"{d:g}" for d in piv_d],
             "damper_pad_class": [f"DP{i + 1}" for i in range(npd)],
             "pivot_bushing": [f"S{j + 1}/{L:g}" for j in range(ns) for L in lengths],
             "endcap_spacer_class": [f"ES{i + 1}" for i in range(sh["spacers"])],
             "cone_spring": [f"CS{i + 1}" for i in range(sh["cones"])],
             "main_spring": [f"M{m + 1}/W{w:.2f}/D{D:g}" for m in range(sh["materials"]) for w in wire_d for D in mbd],
             "bolt": [f"M{d:g}/{c}" for d in bolt_d for c in ("8.8", "9.8", "10.9", "12.9", "14.9")[:sh["bolt_classes"]]]}
    bu_sup, bu_len = np.repeat(np.arange(ns), nl), np.tile(lengths, ns)
    ax_sp = np.concatenate([[-1], np.repeat(np.arange(sh["spacers"]), sh["cones"])])
    ax_cs = np.concatenate([[-1], np.tile(np.arange(sh["cones"]), sh["spacers"])])
    sm = np.repeat(np.arange(sh["materials"]), sh["wires"] * sh["mbds"])
    sw = np.tile(np.repeat(wire_d, sh["mbds"]), sh["materials"])
    sD = np.tile(mbd, sh["materials"] * sh["wires"])
    bo_d = np.repeat(bolt_d, sh["bolt_classes"])
    bo_f = np.tile(cls_f, sh["bolt_formats"])
    options = {"bushing": {"pivot_bushing": np.arange(ns * nl)},
               "axial": {"endcap_spacer_class": ax_sp, "cone_spring": ax_cs},
               "spring": {"main_spring": np.arange(len(sm))},
               "bolt": {"bolt": np.arange(len(bo_d))}}
    option_cost = {"bushing": 0.15 + 0.01 * bu_len * (1 + 0.2 * bu_sup),
                   "axial": np.where(ax_sp < 0, 0.0, 0.25 + 0.05 * np.maximum(ax_sp, 0) + 0.08 * np.maximum(ax_cs, 0)),
                   "spring": 0.9 * mat_cost[sm] * sw ** 2 * sD * 1e-3,   # reference coil count; per app below
                   "bolt": 0.05 * bo_d * bo_f}
    # ---- applications -----------------------------------------------------------------------
    apps = []
    core_grid = np.stack(np.meshgrid(np.arange(nb), np.arange(npv), np.arange(ns), np.arange(-1, npd), indexing="ij"),
                         axis=-1).reshape(-1, 4)
    cb, cp, cs, cd = core_grid.T
    for a in range(n_apps):
        hub = rng.uniform(900.0, 3200.0)                 # N
        arm = rng.uniform(15.0, 30.0)                    # mm
        wet = rng.random() < 0.55                        # belt in oil: axial damping with a pad
        damp = rng.uniform(1.0, 5.0) if wet else 0.0     # Nm axial damping target
        stiff = rng.uniform(3000.0, 16000.0)             # Nmm/rad
        torque = rng.uniform(6e3, 18e3)                  # Nmm, spring torque at nominal
        l_max = rng.uniform(14.0, 24.0)                  # mm, packaging length for the bushing
        od_max = np.sqrt(hub / 2.2) * rng.uniform(1.15, 1.5)   # mm, packaging envelope of the bearing
        bolt_dem = hub * arm / 1e3 * rng.uniform(0.8, 1.2)
        # core constraints: bearing capacity, pivot bending, pivot fits in the bearing bore, pad capacity
        d_req = (hub * arm / 160.0) ** (1 / 3) * 1.6
        piv_dia = piv_d[cp] + 2 * sup_t[cs]
        m_bear = bear_cap[cb] / hub - 1.0
        m_piv = np.minimum(piv_d[cp] / d_req - 1.0, 1.0 - piv_d[cp] / (1.45 * d_req))
        m_env = 1.0 - bear_D[cb] / od_max
        m_bore = 1.0 - piv_dia / (0.62 * bear_D[cb])
        m_pad = np.where(cd < 0, np.where(wet, -1.0, 1.0), np.where(wet, pad_cap[np.maximum(cd, 0)] / max(damp, 1e-9) - 1.0, -1.0))
        mm = np.stack([m_bear, m_piv, m_bore, m_pad, m_env], axis=1)
        ok = np.all(mm >= 0, axis=1)
        idx = np.flatnonzero(ok)
        b, p, s, d = cb[idx], cp[idx], cs[idx], cd[idx]
        cm = mm[idx]
        core_margin = cm.min(axis=1)
        core_binding = np.array(["bearing_hubload", "pivot_bending", "pivot_in_bore", "damper_pad_capacity",
                                 "bearing_envelope"])[cm.argmin(axis=1)] \
            if len(idx) else np.zeros(0, str)
        feasible, margin, group, binding = {}, {}, {}, {}
        # bushing: group (supplier, pivot class); p = F / (d L) <= pmax, L <= packaging length
        g, first = _groups(np.stack([s, p], axis=1)) if len(idx) else (np.zeros(0, int), np.zeros(0, int))
        group["bushing"] = g
        fe, ma, bi = [], [], []
        for k in first:
            pres = hub / (piv_d[p[k]] * bu_len) / sup_pmax[bu_sup]
            mp, ml = 1.0 - pres, 1.0 - bu_len / l_max
            mrow = np.minimum(mp, ml)
            sel = np.flatnonzero((bu_sup == s[k]) & (mrow >= 0))
            fe.append(sel)
            ma.append(mrow[sel])
            bi.append(np.where(mp[sel] < ml[sel], "bushing_pressure", "bushing_length"))
        feasible["bushing"], margin["bushing"], binding["bushing"] = fe, ma, bi
        # axial: group = damper pad; the no-axial option only without a pad
        g, first = _groups(d[:, None]) if len(idx) else (np.zeros(0, int), np.zeros(0, int))
        group["axial"] = g
        fe, ma, bi = [], [], []
        for k in first:
            if d[k] < 0:
                fe.append(np.array([0]))
                ma.append(np.array([np.inf]))
                bi.append(np.array([""]))
                continue
            force = damp * 1e3 / (0.15 * (8 + 2 * d[k]))          # N: damping torque / (mu r_pad)
            sp, co = ax_sp[1:], ax_cs[1:]
            m_sp = spa_cap[sp] / damp - 1.0
            m_co = np.minimum(force / cone_lo[co] - 1.0, 1.0 - force / cone_hi[co])
            mrow = np.minimum(m_sp, m_co)
            sel = np.flatnonzero(mrow >= 0)
            fe.append(sel + 1)
            ma.append(mrow[sel])
            bi.append(np.where(m_sp[sel] < m_co[sel], "spacer_capacity", "cone_force_band"))
        feasible["axial"], margin["axial"], binding["axial"] = fe, ma, bi
        # main spring: group = (housing outer diameter by bearing, inner by pivot, height and torque by pad)
        h_od = 4 * np.round((bear_D[b] * 1.05 + 0.2 * arm) / 4) if len(idx) else np.zeros(0)
        h_id = 3 * np.ceil((piv_d[p] + 2 * sup_t[s] + 2.0) / 3) if len(idx) else np.zeros(0)
        h_ht = 48.0 - np.where(d < 0, 0.0, pad_h[np.maximum(d, 0)])
        t_sp = torque * (1.0 + 0.04 * (d + 1))
        g, first = _groups(np.stack([h_od, h_id, h_ht, t_sp], axis=1)) if len(idx) else (np.zeros(0, int), np.zeros(0, int))
        group["spring"] = g
        n_coil = mat_E[sm] * sw ** 4 / (64 * sD * stiff)                  # active coils for this stiffness
        fe, ma, bi = [], [], []
        for k in first:
            sig = 32 * t_sp[k] / (np.pi * sw ** 3) * (1 + 0.6 * sw / sD)
            parts_m = np.stack([1.0 - sig / mat_sig[sm],                   # stress
                                1.0 - (sD + sw) / h_od[k],                 # outer diameter in the housing
                                (sD - sw) / h_id[k] - 1.0,                 # inner diameter over the pivot
                                np.minimum(n_coil / 2.0 - 1.0, 1.0 - n_coil / 15.0),   # coil count window
                                1.0 - (n_coil + 1.5) * sw * 1.1 / h_ht[k]], axis=1)    # solid height
            mrow = parts_m.min(axis=1)
            sel = np.flatnonzero(mrow >= 0)
            fe.append(sel)
            ma.append(mrow[sel])
            bi.append(np.array(["spring_stress", "spring_outer_diameter", "spring_inner_diameter", "coil_count",
                                "solid_height"])[parts_m[sel].argmin(axis=1)])
        feasible["spring"], margin["spring"], binding["spring"] = fe, ma, bi
        # bolt: group = pivot class (the bolt passes through the pivot); capacity and fit
        g, first = _groups(p[:, None]) if len(idx) else (np.zeros(0, int), np.zeros(0, int))
        group["bolt"] = g
        fe, ma, bi = [], [], []
        for k in first:
            m_cap = bo_d ** 2 * bo_f * 1.1 / bolt_dem - 1.0
            m_fit = 1.0 - (bo_d + 3.0) / piv_d[p[k]]
            mrow = np.minimum(m_cap, m_fit)
            sel = np.flatnonzero(mrow >= 0)
            fe.append(sel)
            ma.append(mrow[sel])
            bi.append(np.where(m_cap[sel] < m_fit[sel], "bolt_capacity", "pivot_wall"))
        feasible["bolt"], margin["bolt"], binding["bolt"] = fe, ma, bi
        spring_cost = option_cost["spring"] * n_coil / 6.0
        apps.append(AppFeasibility(
            app_id=f"APP-{a:04d}",
            core_parts={"ball_bearing": b, "pivot_class_diameter_mm": p, "damper_pad_class": d},
            core_cost_eur=bear_cost[b] + np.where(d < 0, 0.0, pad_cost[np.maximum(d, 0)]),
            core_margin=core_margin, group=group, feasible=feasible, option_margin=margin,
            volume=float(np.round(rng.lognormal(np.log(80e3), 0.8), -2)),
            option_cost_eur={"spring": spring_cost},
            core_binding=core_binding, option_binding=binding,
            note="" if len(idx) else "no core passes bearing capacity, pivot bending and bore fit"))
    return PortfolioFeasibility(apps=apps, parts=parts, part_cost_eur=default_fixed_costs(parts),
                                options=options, option_cost_eur=option_cost,
                                notes=["synthetic feasibility data (synth.platform.synthetic): illustrative numbers"])
