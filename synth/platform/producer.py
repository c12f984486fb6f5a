"""The feasible (group, option) pairs of a chunk of applications: what ``synth rationalise`` reads, through the one
evaluator (the portfolio read, split into chunks and run across processes or Dask is
:mod:`synth.platform.portfolio_feasibility`).

:func:`chunk_feasibility` fills the applications of :class:`~synth.platform.data.PortfolioFeasibility` from
validated design inputs with the group functions of :mod:`synth.design.evaluate`,
called once per chunk of applications with the rows of all of them (the
applications axis, as the bulk engine):

1. the inputs and every core the application may use (:func:`synth.design.space.core_rows`):
   the feasible cores pass the input-only and the core constraints;
2. per subsystem, the **group** of each feasible core: the core values that subsystem's
   group function reads (:func:`group_keys`); cores of one application with the same
   key accept the same options, so each group is evaluated once, on one representative
   core, against every candidate option;
3. per group, the feasible options with their smallest margin (the margin objective's,
   :meth:`synth.design.evaluate.Group.min_margin`) and binding constraint.

Candidate options are every option of the subsystem except those that fail whatever
the core: bushings of another supplier than the core's, axial options of another
damper pad (or "none" with a pad), main springs outside the housing's mean-diameter
window (their inner or outer diameter would hit the housing). The main springs, the
bulk of the work, go in two stages: per (application, nominal spring torque) the
constraints that see the key only through that torque (:data:`SPRING_TORQUE_ONLY`: the
stresses, the index range, the wire section), then each key against the springs that
passed, through the whole group; a spring failing stage 1 fails every key of that
torque, so the feasible sets are exactly those of evaluating every key against every
spring (``tests/test_platform_real.py`` compares both, and checks that no spring outside
the window is feasible).

An application with no complete design (a feasible core whose four groups each have a
feasible option) gets a ``note`` saying why: by default the nearest *evaluated* design
(the core, or the feasible core and options, with the largest smallest margin, and the
constraints it misses); with ``diagnose=True`` the nearest design of the whole catalog
product by :func:`synth.optimise.diagnose.diagnose` (about a second per application).
"""

from __future__ import annotations

import time

import numpy as np

from synth import catalog
from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.assessment import assess_group, columns_of, passes
from synth.design.bolt_group import bolt_codes, bolt_reads
from synth.design.combine import combine
from synth.design.constraints import REGISTRY
from synth.design.space import SUBSYSTEMS, core_rows, spring_window
from synth.errors import InputError
from synth.platform.data import AppFeasibility, Names, ScaledCost
from synth.platform.options import Catalogue, catalogue
from synth.platform.pairs import (BLOCK_PAIRS, NO_BINDING, Pairs, binding_name, binding_names, blocks,
                                  margins_and_binding)
from synth.kernels import engines, main_spring
from synth.kernels.main_spring import keys_of_rows
from synth.optimise.diagnose import diagnose
from synth.optimise.objectives import goal

__all__ = ["chunk_feasibility", "group_keys", "SPRING_TORQUE_ONLY", "SPRING_STAGES", "margins_and_binding",
           "spring_group", "BLOCK_PAIRS", "AXIAL_ENGINE", "MARGIN_TOL"]


def group_keys(core: dict) -> dict:
    """Subsystem -> the core values its group reads (besides the application): the group key. What each group
    function declares and what the registry's checks read of the core now (:func:`synth.design.evaluate.core_values`
    of ``core``, a core group's values), with the core's bushing supplier and damper pad, which decide its options."""
    return {"bushing": ("supplier_code", *evaluate.core_values("bushing", core)),
            "axial": ("pad_code", *evaluate.core_values("axial", core)),
            "spring": evaluate.core_values("spring", core),
            "bolt": evaluate.core_values("bolt", core)}
#: spring constraints whose margins depend on the key only through the nominal spring torque (and the
#: application): the stresses (eq. 69-77, figure 71) and the option-only index range and wire section
SPRING_TORQUE_ONLY = ("spring_yield", "spring_static_permissible", "spring_fatigue", "spring_index_min",
                      "spring_index_max", "spring_material_section")
#: the stages of the main-spring evaluation: (key columns, the constraints whose margins depend on the key only
#: through them); each stage's columns contain the previous ones, a spring failing a stage is dropped for every
#: key of that stage group (the coil gap, eq. (89)-(93), sees the torque and the housing height only). The third
#: item ``(column, direction)`` says how the stage's margins move with one column, everything else held:
#: ``+1`` they do not increase as it grows, ``-1`` they do not decrease. The torque-only margins do not increase
#: with the nominal torque (for one application and spring): the working angles grow with it (eq. 66-70), the
#: stresses are linear in the torques (eq. 71-77), the Goodman factor falls as the mean stress grows at a fixed
#: or growing amplitude (figure 71). The coil gap ``(H - b)/n - b`` grows with the housing height H. So the
#: stage groups are evaluated in rounds along that column, and a spring that failed at one value is not tried
#: again where it must fail too.
SPRING_STAGES = ((("spring_torque_nominal_nm",), SPRING_TORQUE_ONLY, ("spring_torque_nominal_nm", +1)),
                 (("spring_torque_nominal_nm", "spring_housing_height_mm"), ("spring_coil_gap",),
                  ("spring_housing_height_mm", -1)))
#: the axial group's engine this path takes (:func:`synth.kernels.engines.axial`; ``Settings(engine="numpy")``
#: overrides it): the compiled wear, about 3x the numpy reference's speed on the feasibility data
#: (``benchmarks/bench_platform.py``); ``"numpy"`` gives the design path's margins bit for bit
AXIAL_ENGINE = "numba"
#: how far an option margin may stand from the design path's (``synth.optimise.product``, the numpy reference):
#: the compiled wear agrees within :data:`synth.kernels.axial.RTOL` (1e-12) relative; the feasible options, the
#: binding constraints and the chosen parts are the same (``tests/test_platform_real.py``)
MARGIN_TOL = 1e-9

def spring_group(apps, keys: dict, k, options, settings: evaluate.Settings, spring_keys=None) -> evaluate.Group:
    """The main-spring group's registry margins for rows pairing key ``k[i]`` with option ``options[i]``: the
    compiled kernels (:func:`synth.kernels.main_spring.pair_margins`, equal to the registry's spring group,
    ``tests/test_kernels.py``), 10-15x the numpy group on these pairs, where they cover the registry's checks under
    ``settings`` (:func:`synth.kernels.engines.spring`: no design rule on a spring check, the thesis's limit
    basis), else the numpy twin.

    ``options``: rows of the design space's spring table (integers), or the table's columns for each row (a
    dict, as :func:`synth.design.evaluate.spring` takes them). ``spring_keys``: the keys' kernel table when the
    caller made it once (:func:`synth.kernels.main_spring.keys_of_rows`). The group holds the margins of the
    non-advisory constraints (feasibility, the margin objective and the nearest design read no other) and the
    application of each row; a fatigue check without its durability test has the margin ``+inf``, as the
    registry's "not verified"."""
    kk = spring_keys if spring_keys is not None else main_spring.keys_of_rows(apps, keys)
    k = np.asarray(k, dtype=np.int64)
    if isinstance(options, dict):
        opts, rows = main_spring.options_of_space(options, np.arange(len(k))), np.arange(len(k))
    else:
        opts, rows = main_spring.options_of_space(), np.asarray(options, dtype=np.int64)
    m = main_spring.pair_margins(kk, opts, k, rows, engine=engines.spring(settings, "numba"), settings=settings)
    return evaluate.Group("spring", {"app": np.asarray(keys["app"])[k]},
                          {name: m[:, c] for c, name in enumerate(main_spring.checks())}, rules=settings.rules)


# --------------------------------------------------------------------------------------------------------- chunk

def _group_ids(values: dict, pos: np.ndarray, cols: tuple, extra: dict | None = None):
    """Group id (global in the chunk, contiguous per application) of rows ``pos``; a representative row each."""
    extra = extra or {}
    vals = [values["app"][pos].astype(float)]
    for k in cols:
        v = extra[k][pos] if k in extra else values[k][pos]
        vals.append(np.nan_to_num(np.asarray(v, dtype=float), nan=-1.0, posinf=1e300, neginf=-1e300))
    if not len(pos):
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    uniq, first, inv = np.unique(np.stack(vals, axis=1), axis=0, return_index=True, return_inverse=True)
    return np.asarray(inv).reshape(-1), pos[first]


def chunk_feasibility(inputs: list, ids: list, volumes, settings: evaluate.Settings = evaluate.DEFAULT, *,
                      diagnose: bool = False, stats: dict | None = None) -> list:
    """:class:`~synth.platform.data.AppFeasibility` of each validated input (one vectorised evaluation) under the
    configuration ``settings`` (its user catalogs read here: a Dask worker process has its own).

    ``stats`` (a dict) receives the seconds and the evaluated pairs of each group (added to what it holds).
    """
    with catalog.using(settings.catalogs):
        return _chunk_feasibility(inputs, ids, volumes, settings, diagnose, stats)


def _chunk_feasibility(inputs, ids, volumes, settings, diagnose, stats) -> list:
    st = stats if stats is not None else {}
    clock = [time.perf_counter()]

    def lap(name, pairs=0):
        now = time.perf_counter()
        st[f"{name}_s"] = st.get(f"{name}_s", 0.0) + now - clock[0]
        st[f"{name}_pairs"] = st.get(f"{name}_pairs", 0) + int(pairs)
        clock[0] = now

    cat = catalogue()
    sp = cat.space
    n = len(inputs)
    if n == 0:
        return []
    apps = Applications.of(inputs)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        ig = evaluate.inputs(apps, np.arange(n), settings)
        per_app = [core_rows(sp, d) for d in inputs]
        a = np.concatenate([np.full(len(c), i, dtype=np.int64) for i, c in enumerate(per_app)])
        crow = np.concatenate(per_app).astype(np.int64)
        cg = evaluate.core(apps, a, sp.rows("core", crow), settings)
        ok = cg.ok() & ig.ok()[a]
        core_m, core_b = margins_and_binding(cg, True)
        im, ib = margins_and_binding(ig, False)
        all_m, all_b = margins_and_binding(cg, False)
        worse = im[a] < all_m
        all_m, all_b = np.where(worse, im[a], all_m), np.where(worse, ib[a], all_b)
        pos = np.flatnonzero(ok)
        extra = {"pad_code": sp.tables["core"]["pad_code"][crow]}
        gid, rep, pairs = {}, {}, {}
        keys = group_keys(cg.values)
        for s in SUBSYSTEMS:
            gid[s], rep[s] = _group_ids(cg.values, pos, keys[s], extra)
            pairs[s] = Pairs(len(rep[s]))
        lap("core", len(a))
        lap("bushing", _bushing(apps, cat, cg, rep["bushing"], settings, pairs["bushing"]))
        lap("axial", _axial(apps, cat, cg, rep["axial"], extra["pad_code"], settings, pairs["axial"]))
        n1, n2 = _spring(apps, cat, cg, rep["spring"], settings, pairs["spring"])
        st["spring_stage1_pairs"] = st.get("spring_stage1_pairs", 0) + n1
        lap("spring", n1 + n2)
        lap("bolt", _bolt(apps, cat, cg, rep["bolt"], settings, pairs["bolt"]))
        lap("axial", _judge_undecided(apps, cat, cg, a, pos, gid, rep, pairs, extra["pad_code"], settings))
        lap("reasons", _nearest_springs(apps, cat, cg, a, pos, all_m, gid, rep, pairs, settings))
        out = _assemble(inputs, ids, volumes, apps, cat, a, crow, pos, core_m, core_b, all_m, all_b, gid, rep, pairs,
                        diagnose, settings)
    lap("assemble")
    return out


def _bushing(apps, cat, cg, rep, settings, acc: Pairs):
    sup = cat.space.tables["bushing"]["supplier_code"]
    gp, op = np.nonzero(cg.values["supplier_code"][rep][:, None] == sup[None, :])
    for blk in blocks(len(gp)):
        g, o = gp[blk], op[blk]
        acc.add(g, o, evaluate.bushing(apps, cg, rep[g], cat.space.rows_read("bushing", cat.option_row["bushing"][o]), settings))
    return len(gp)


def _axial(apps, cat, cg, rep, pad_code, settings, acc: Pairs, group=evaluate.axial_judged):
    pad = pad_code[rep]
    nr = cat.n_axial_real
    cnt = np.where(pad < 0, 1, nr)
    gp = np.repeat(np.arange(len(rep)), cnt)
    j = np.arange(len(gp)) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    op = np.where(pad[gp] < 0, cat.axial_none, cat.axial_option(np.maximum(pad[gp], 0), j))
    engine = engines.axial(settings, AXIAL_ENGINE)
    cut = group is evaluate.axial_judged   # the search: the wear solved only where the checks before it pass
    skipped = []
    for blk in blocks(len(gp), BLOCK_PAIRS // 4):
        g, o = gp[blk], op[blk]
        if cut:
            pre = evaluate.axial_before_wear(apps, cg, rep[g], cat.space.rows_read("axial", cat.option_row["axial"][o]),
                                             settings, engine=engine).ok()
            if not pre.all():
                skipped.append(g[~pre])
                g, o = g[pre], o[pre]
        if len(g):
            acc.add(g, o, group(apps, cg, rep[g], cat.space.rows_read("axial", cat.option_row["axial"][o]),
                                settings, engine=engine))
    if skipped:
        _without_a_pass(apps, cat, cg, rep, gp, op, np.unique(np.concatenate(skipped)), settings, acc, group, engine)
    return len(gp)


def _without_a_pass(apps, cat, cg, rep, gp, op, groups, settings, acc: Pairs, group, engine) -> None:
    """The groups ``groups`` (some of whose pairs failed a check before the wear and were not solved) that have no
    feasible pair: every pair of theirs again with the whole group, so that their nearest option (the largest
    smallest margin, :func:`~synth.design.combine.nearest_rank`) is the one every pair evaluated gives. Where a
    group has a feasible pair, an unsolved pair (infeasible: it fails a check the whole group holds with the same
    margin) ranks below it and changes nothing."""
    has = np.zeros(len(rep), bool)
    for x in acc.g:
        has[x] = True
    again = groups[~has[groups]]
    if not len(again):
        return
    acc.best[again], acc.best_b[again] = -np.inf, NO_BINDING
    sel = np.flatnonzero(np.isin(gp, again))
    for blk in blocks(len(sel), BLOCK_PAIRS // 4):
        g, o = gp[sel[blk]], op[sel[blk]]
        acc.add(g, o, group(apps, cg, rep[g], cat.space.rows_read("axial", cat.option_row["axial"][o]), settings,
                            engine=engine))


def _judge_undecided(apps, cat, cg, a, pos, gid, rep, pairs, pad_code, settings) -> int:
    """At fidelity ``screening`` (axial options screened, then judged: :func:`synth.design.evaluate.axial_judged`),
    "no complete design" must be the full model's verdict too: for an application without a complete design some
    of whose cores lack only an axial option, its axial groups are evaluated again with the full model alone (the
    screening model may reject options the full model passes: :func:`synth.design.evaluate.axial_full`). Returns
    the rows evaluated."""
    if settings.judge is settings or not len(pos):
        return 0
    has = {s: np.bincount(np.concatenate(pairs[s].g) if pairs[s].g else np.zeros(0, np.int64),
                          minlength=len(rep[s])) > 0 for s in SUBSYSTEMS}
    others = has["bushing"][gid["bushing"]] & has["spring"][gid["spring"]] & has["bolt"][gid["bolt"]]
    complete = others & has["axial"][gid["axial"]]
    done = np.zeros(int(a.max()) + 1, bool)
    done[a[pos[complete]]] = True
    undecided = np.zeros(len(done), bool)
    undecided[a[pos[others & ~done[a[pos]]]]] = True
    groups = np.unique(gid["axial"][undecided[a[pos]]])  # every axial group of those applications
    if not len(groups):
        return 0
    acc = pairs["axial"]
    keep = [~np.isin(g, groups) for g in acc.g]
    acc.g, acc.o, acc.m, acc.b = ([x[k] for x, k in zip(xs, keep)] for xs in (acc.g, acc.o, acc.m, acc.b))
    acc.best[groups], acc.best_b[groups] = -np.inf, NO_BINDING
    full = Pairs(len(groups))
    n = _axial(apps, cat, cg, rep["axial"][groups], pad_code, settings, full, evaluate.axial_full)
    acc.g.extend(groups[g] for g in full.g)
    acc.o.extend(full.o)
    acc.m.extend(full.m)
    acc.b.extend(full.b)
    acc.best[groups], acc.best_b[groups] = full.best, full.best_b
    return n


def _spring(apps, cat, cg, rep, settings, acc: Pairs, compiled_rounds: bool = True):
    """Main springs in stages (:data:`SPRING_STAGES`), then every key against the survivors, in its window.

    The stages' rounds run in one compiled pass each (:func:`synth.kernels.main_spring.stage_round`) where the
    compiled kernels cover the registry's spring checks and ``compiled_rounds``; else block by block through the
    spring group and its assessment (the numpy twin's path; the same survivors, failures and best margins,
    ``tests/test_rationalise_speed.py``). Returns the pairs judged in the stages and evaluated in the last (exact)
    evaluation.
    """
    if not len(rep):
        return 0, 0
    keys = evaluate.spring_keys(cg, rep)
    kk = keys_of_rows(apps, keys)  # the keys' kernel table, once
    jit = main_spring.load_rounds()
    rows = cat.option_row["spring"]
    mbd = cat.space.tables["spring"]["main_spring_mean_body_diameter_mm"][rows]
    lo, hi = spring_window(keys["spring_housing_inner_diameter_mm"], keys["spring_housing_outer_diameter_mm"])
    kpos = np.arange(len(rep))
    window = (lambda lo_, hi_: (mbd[None, :] >= lo_[:, None]) & (mbd[None, :] <= hi_[:, None]))  # noqa: E731
    n_stage = n_last = 0
    stages, prev_of, prev = [], None, None
    compiled = compiled_rounds and engines.spring(settings, "numba") == "numba"   # the kernels cover the checks
    opts = main_spring.options_of_space() if compiled else None
    for cols, ids, (mcol, direction) in SPRING_STAGES:
        of, srep = _group_ids(keys, kpos, cols)        # stage group of each key; a representative key each
        ng = len(srep)
        g_lo, g_hi = np.full(ng, np.inf), np.full(ng, -np.inf)
        np.minimum.at(g_lo, of, lo)                    # the union of its keys' windows
        np.maximum.at(g_hi, of, hi)
        parent = None if prev_of is None else prev_of[srep]
        survive = np.zeros((ng, len(rows)), bool)
        best, best_b = np.full(ng, -np.inf), np.full(ng, NO_BINDING, np.int16)
        # rounds along the monotone column within the groups equal on the other columns ("lines"): a spring that
        # failed in a line is not tried again further along it
        line, _ = _group_ids(keys, srep, tuple(c for c in cols if c != mcol))
        val = np.asarray(keys[mcol][srep], dtype=float)
        order = np.lexsort((direction * val, line))
        rank = np.empty(ng, np.int64)
        rank[order] = np.arange(ng) - np.searchsorted(line[order], line[order])
        failed = np.zeros((int(line.max()) + 1 if ng else 0, len(rows)), bool)
        line = np.ascontiguousarray(line, np.int64)
        finite = np.isfinite(val)
        for rk in range(int(rank.max()) + 1 if ng else 0):
            # a round's candidates at once (a line has one group per round: what fails now is for later rounds)
            if compiled:   # window, margins, smallest and record in one compiled pass (the same doubles)
                cols, bind = _stage_columns(ids)
                n_stage += main_spring.stage_round(
                    np.flatnonzero(rank == rk), g_lo, g_hi, mbd, kk, srep, opts, rows, cols, bind,
                    no_binding=NO_BINDING, finite=finite, line=line, survive=survive, failed=failed, best=best,
                    best_b=best_b, exclude=failed, exclude_row=line, need=prev, need_row=parent)
                continue
            for gg_, oo in main_spring.window_pairs(np.flatnonzero(rank == rk), g_lo, g_hi, mbd, exclude=failed,
                                                    exclude_row=line, need=prev, need_row=parent, limit=BLOCK_PAIRS):
                n_stage += len(gg_)
                m, b = _stage_margin(spring_group(apps, keys, srep[gg_], rows[oo], settings, kk), ids)
                jit.record_stage(gg_, oo, passes(m), m, b, finite, line, survive, failed, best, best_b)
        stages.append((of, survive, best, best_b))
        prev_of, prev = of, survive
    # every key against the survivors of its last-stage group, in its own window: the exact group
    for g, o in main_spring.window_pairs(kpos, lo, hi, mbd, need=prev, need_row=prev_of, limit=BLOCK_PAIRS):
        n_last += len(g)
        acc.add(g, o, spring_group(apps, keys, g, rows[o], settings, kk))
    # keys left without a candidate: the first stage that left none in their window says why
    left = np.flatnonzero(~acc.evaluated)
    for of, survive, best, best_b in stages:
        if not len(left):
            break
        empty = ~(survive[of[left]] & window(lo[left], hi[left])).any(axis=1)
        k = left[empty]
        acc.best[k], acc.best_b[k] = best[of[k]], best_b[of[k]]
        acc.evaluated[k] = np.isfinite(best[of[k]])
        left = left[~empty]
    return n_stage, n_last


def _nearest_springs(apps, cat, cg, a, pos, all_m, gid, rep, pairs, settings, rounds: int = 64) -> int:
    """For an application with no complete design whose nearest core has no feasible main spring, that core's
    spring key against every spring of its window: the nearest spring over every constraint (the stages only
    know the margins of their own constraints over the springs that reached them). Repeated until the nearest
    core's spring is known exactly, so the reason names what that design really misses. Returns the rows
    evaluated."""
    has = {s: np.bincount(np.concatenate(pairs[s].g) if pairs[s].g else np.zeros(0, np.int64),
                          minlength=len(rep[s])) > 0 for s in SUBSYSTEMS}
    complete = np.ones(len(pos), bool)
    for s in SUBSYSTEMS:
        complete &= has[s][gid[s]]
    todo = [np.flatnonzero(a[pos] == i) for i in np.unique(a[pos])]
    todo = [k for k in todo if not complete[k].any()]
    acc = pairs["spring"]
    refined = np.zeros(len(rep["spring"]), bool) | has["spring"]
    rows = cat.option_row["spring"]
    mbd = cat.space.tables["spring"]["main_spring_mean_body_diameter_mm"][rows]
    n = 0
    for _ in range(rounds):
        val = combine(all_m[pos], [np.where(has[s][gid[s]], np.inf, pairs[s].best[gid[s]]) for s in SUBSYSTEMS])
        groups = {int(gid["spring"][k[int(np.argmax(val[k]))]]) for k in todo}
        todo = [k for k in todo if not refined[gid["spring"][k[int(np.argmax(val[k]))]]]]
        groups = np.array(sorted(g for g in groups if not refined[g]), np.int64)
        if not len(groups):
            break
        keys = evaluate.spring_keys(cg, rep["spring"][groups])
        kk = keys_of_rows(apps, keys)
        lo, hi = spring_window(keys["spring_housing_inner_diameter_mm"], keys["spring_housing_outer_diameter_mm"])
        g, o = np.nonzero((mbd[None, :] >= lo[:, None]) & (mbd[None, :] <= hi[:, None]))
        best = Pairs(len(groups))
        for blk in blocks(len(g)):
            best.add(g[blk], o[blk], spring_group(apps, keys, g[blk], rows[o[blk]], settings, kk))
        acc.best[groups], acc.best_b[groups], acc.evaluated[groups] = best.best, best.best_b, best.evaluated
        refined[groups] = True
        n += len(g)
    return n


def _stage_margin(grp: evaluate.Group, ids: tuple):
    """Smallest margin of the (non-advisory) constraints ``ids`` per row, and where it is reached: the group's
    assessment over those checks (:func:`margins_and_binding`)."""
    m, b = assess_group(grp, only=ids).objective_binding(False)
    return m, np.where(b < 0, NO_BINDING, b).astype(np.int16)


def _stage_columns(ids: tuple) -> tuple:
    """``(columns, bindings)`` of a stage's checks ``ids`` for :func:`synth.kernels.main_spring.stage_round`: the
    kernel columns (:func:`synth.kernels.main_spring.checks`) of the counted ones the compiled group holds, in the
    assessment's order (:func:`_stage_margin`), and their registry indices."""
    names = main_spring.checks()
    cols = columns_of(tuple(c for c in ids if c in names))
    dec = list(cols.decisive)
    return (np.array([names.index(cols.ids[j]) for j in dec], np.int64),
            np.asarray(cols.index[dec] if dec else np.zeros(0), np.int64))


def _bolt(apps, cat, cg, rep, settings, acc: Pairs):
    """Every bolt option against the groups ``rep``: the group once per group and bolt as it reads it
    (:func:`synth.design.bolt_group.bolt_codes`: bolts equal in every column it reads have the same values and
    margins), each pair recorded with its key's row, in option order. Returns the pairs judged."""
    if not len(rep):
        return 0
    nb = cat.n_options("bolt")
    rows = cat.option_row["bolt"]
    t = cat.space.tables["bolt"]
    code, first = bolt_codes({k: np.asarray(t[k])[rows] for k in bolt_reads(settings) if k in t}, settings)
    nk = len(first)
    ua, slot = np.unique(cg.values["app"][rep], return_inverse=True)
    slot = np.asarray(slot).reshape(-1)
    fa, fb = (x.ravel() for x in np.meshgrid(ua, first, indexing="ij"))
    fix = evaluate.fixation_values(apps, fa, cat.space.rows_read("bolt", rows[fb]), settings)   # per application and key
    per = max(BLOCK_PAIRS // nb, 1)  # groups per block (all their bolts)
    for lo in range(0, len(rep), per):
        gs = np.arange(lo, min(lo + per, len(rep)))
        g, k = (x.ravel() for x in np.meshgrid(gs, np.arange(nk), indexing="ij"))
        idx = slot[g] * nk + k
        grp = evaluate.bolt(apps, cg, rep[g], cat.space.rows_read("bolt", rows[first[k]]), settings,
                            fixation={key: v[idx] for key, v in fix.items()})
        gp, op = (x.ravel() for x in np.meshgrid(gs, np.arange(nb), indexing="ij"))
        acc.add(gp, op, grp, row=(gp - lo) * nk + code[op])
    return len(rep) * nb


def _core_text(cat: Catalogue, row: int) -> str:
    t = cat.space.tables["core"]
    return (f"{t['ball_bearing'][row]}, pivot class {t['pivot_class_diameter_mm'][row]:g} mm, bushing supplier "
            f"{t['pivot_bushing_supplier'][row]}, damper pad {t['damper_pad_class'][row]}")


def _assemble(inputs, ids, volumes, apps, cat, a, crow, pos, core_m, core_b, all_m, all_b, gid, rep, pairs,
              diagnose, settings) -> list:
    n = len(inputs)
    grouped = {s: pairs[s].by_group(len(rep[s])) for s in SUBSYSTEMS}
    # the options as int32 and the binding names as int16 codes into one table (issue 36: the feasibility data are
    # most of the command's memory, about 175 MB per 1,000 applications with int64 options and name pointers)
    table = np.array(list(REGISTRY) + [""], dtype=object)
    grouped = {s: (ptr, o.astype(np.int32), m, np.minimum(b, len(table) - 1).astype(np.int16))
               for s, (ptr, o, m, b) in grouped.items()}
    has_option = {s: np.diff(g[0]) > 0 for s, g in grouped.items()}   # per group: a feasible option
    app_of_group = {s: a[rep[s]] for s in SUBSYSTEMS}
    first_group = {s: np.searchsorted(app_of_group[s], np.arange(n + 1)) for s in SUBSYSTEMS}
    pos_app = a[pos]
    # each application's spring costs, cat.spring_cost_eur(stiffness), computed when read from one vector
    spring_numerator = cat.space.tables["spring"]["cost_eur_times_stiffness"][cat.option_row["spring"]]
    out = []
    for i in range(n):
        sel = pos[pos_app == i]                  # chunk rows of the feasible cores of application i
        k = np.flatnonzero(pos_app == i)         # their positions in ``pos`` (the group ids' index)
        group, feasible, margin, binding = {}, {}, {}, {}
        complete = np.ones(len(sel), bool)
        for s in SUBSYSTEMS:
            g0, g1 = first_group[s][i], first_group[s][i + 1]
            group[s] = gid[s][k] - g0
            ptr, o, m, b = grouped[s]
            feasible[s] = [o[ptr[g]:ptr[g + 1]] for g in range(g0, g1)]
            margin[s] = [m[ptr[g]:ptr[g + 1]] for g in range(g0, g1)]
            binding[s] = [Names(b[ptr[g]:ptr[g + 1]], table) for g in range(g0, g1)]
            complete &= has_option[s][g0:g1][group[s]]
        d = inputs[i]
        af = AppFeasibility(
            app_id=str(ids[i]), core_parts={f: cat.core_codes[f][crow[sel]] for f in cat.core_codes},
            core_cost_eur=goal("cost").core(cat.space, crow[sel], {}), core_margin=core_m[sel],
            group=group, feasible=feasible, option_margin=margin, volume=float(volumes[i]),
            option_cost_eur={"spring": ScaledCost(spring_numerator, float(apps.spring_stiffness_nm_per_deg[i]))},
            core_binding=binding_names(core_b[sel]), option_binding=binding,
            core_rows=crow[sel])
        if not complete.any():
            af.note = _why(cat, i, a, crow, all_m, all_b, sel, k, gid, first_group, pairs)
            if diagnose:
                af.note = _diagnosed(d, settings, af.note)
        out.append(af)
    return out


def _why(cat, i, a, crow, all_m, all_b, sel, k, gid, first_group, pairs) -> str:
    """The nearest evaluated design of an application with no complete design, and what it misses."""
    if not len(sel):
        rows = np.flatnonzero(a == i)
        if not len(rows):
            return "no design: no core of the catalogs is allowed for this application"
        j = rows[int(np.argmax(all_m[rows]))]
        return (f"no feasible core: the nearest ({_core_text(cat, int(crow[j]))}) misses {binding_name(all_b[j])} "
                f"(margin {all_m[j]:+.3f})")
    val = combine(all_m[sel], [pairs[s].best[gid[s][k]] for s in SUBSYSTEMS])
    c = int(np.argmax(val))
    miss = []
    for s in SUBSYSTEMS:
        g = gid[s][k][c]
        if pairs[s].best[g] < 0:
            what = (f"{binding_name(pairs[s].best_b[g])} ({pairs[s].best[g]:+.3f})" if pairs[s].evaluated[g]
                    else "no candidate option")
            miss.append(f"{s}: {what}")
    return (f"no complete design: the nearest evaluated design ({_core_text(cat, int(crow[sel[c]]))}) misses "
            + "; ".join(miss))


def _diagnosed(d, settings, fallback: str) -> str:
    try:
        r = diagnose(d, relax=False, settings=settings)
    except InputError as exc:  # pragma: no cover - a validated input evaluates
        return f"{fallback} (diagnosis failed: {exc})"
    v = (r.diagnosis or {}).get("violated") or []
    if not v:
        return fallback
    return "no feasible design (synth.optimise.diagnose): the nearest design misses " + ", ".join(
        f"{x['constraint']} ({x['margin']:+.3f})" for x in v)
