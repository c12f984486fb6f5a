"""Bulk screening engine: one row per application, the same answer as ``solve(d, objective, "enumerate")``.

:func:`screen_applications` is the public entry point (the contract with the
bulk harness). It evaluates a chunk of applications together, on the
applications axis of the one evaluator (:mod:`synth.design.evaluate`): every
group function is called once per chunk with the rows of all applications,
never once per application. :func:`screen_applications_reference` loops over
:func:`synth.optimise.solve` and is the definition of the right answer that
the tests compare the fast path with.

Fast path, for additive objectives (``standard``, ``cost``, their orders and
weighted sums without the margin):

1. inputs and cores of every application (rows ``(application, core)``);
2. per feasible core, the cheapest feasible option of each subsystem, the
   options evaluated **in score order with early exit** (growing blocks; a
   stable order keeps the reference's lowest-index tie-break), the main spring
   once per distinct spring key;
3. per application the core with the smallest total score;
4. the chosen designs re-verified together through the registry's groups.

Objectives with the margin and infeasible applications (their nearest design
and diagnosis) take the per-application path.

Columns of the result (exactly, in this order): see :func:`columns`.
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np
import pandas as pd

from synth.design import evaluate
from synth.design.constraints import EVALUATED_GROUPS, REGISTRY, version
from synth.design.result import FAIL, PASS, WARNING
from synth.design.space import PART_KEYS, SUBSYSTEMS, axial_attributes
from synth.errors import InputError
from synth.optimise import solve
from synth.design.applications import DEFAULTS
from synth.design.evaluate import NOT_VERIFIED
from synth.design.assessment import assess
from synth.optimise.product import core_scores, option_scores
from synth.design.verify import evaluate_design, parts_of_rows
from synth.optimise.batch import Batch, robust
from synth.optimise.diagnose import layout_switches, probe_batch, relaxations_batch
from synth.optimise import objectives
from synth.optimise.objectives import FALLBACK_WEIGHTS, Objective, with_margin_tiebreak
from synth.bulk.capability import COLUMNS as CAPABILITY_COLUMNS, NUMBERS as CAPABILITY_NUMBERS

__all__ = ["columns", "constraint_ids", "screen_applications", "screen_applications_reference", "row_from_result"]


def constraint_ids() -> list:
    """The registry constraints a bulk row reports a margin for (the evaluator's groups: not the 3D model's, not
    the shrink fit's)."""
    return [cid for cid, c in REGISTRY.items() if c.group in EVALUATED_GROUPS]


def columns() -> list:
    """The result columns, in order (the contract with the harness).

    >>> cols = columns()
    >>> cols[:2], "part_ball_bearing" in cols, "margin_self_locking" in cols, cols[-1]
    (['feasible', 'status'], True, True, 'notes')
    """
    return (["feasible", "status", "verdict"] + [g.column for g in objectives.GOALS]
            + [f"part_{k}" for k in PART_KEYS]
            + ["margin_min", "binding_constraint", "binding_margin"]
            + [f"margin_{n}" for n in constraint_ids()]
            + list(CAPABILITY_COLUMNS) + ["violated", "relaxation", "notes"])


def _num(v):
    return float(v) if v is not None else math.nan


def _g(x) -> str:
    return f"{float(x):.6g}"


def _fmt_relaxation(rel: dict) -> str:
    return ", ".join(f"{name} {_g(ch['from'])}->{_g(ch['to'])}" for name, ch in rel["inputs"].items())


def row_from_result(res, diagnose: bool = True) -> dict:
    """One result row (dict of :func:`columns`) from a :class:`~synth.design.result.Result`.

    ``binding_constraint`` is the design's most critical constraint: the
    smallest margin counted in the margin objective when feasible, the most
    violated constraint when infeasible; ``margin_min`` is the smallest margin
    of all evaluated (non-advisory) constraints. Constraints that are not
    verified or do not apply have no margin (NaN); ``notes`` says why.
    """
    feasible = res.status in ("optimal", "feasible") and not res.failed()
    row = {"feasible": bool(feasible), "status": "optimal" if feasible else "infeasible", "verdict": res.verdict,
           **{g.column: _num(res.objectives.get(g.name)) for g in objectives.GOALS}}
    for k in PART_KEYS:
        row[f"part_{k}"] = res.parts.get(k)
    a = res.assessment()  # the one judgement (:mod:`synth.design.assessment`), as the fast path's rows
    row["margin_min"] = float(a.margin_min[0])
    row["binding_constraint"], row["binding_margin"] = str(a.binding_ids()[0]), float(a.binding_margin[0])
    failed = sorted(res.failed(), key=lambda c: c.margin)
    every = {c.id: c.margin for c in res.checks if c.margin is not None and c.verdict in (PASS, FAIL, WARNING)}
    for n in constraint_ids():  # advisory constraints carry their margin, passing or warning
        row[f"margin_{n}"] = float(every[n]) if n in every else math.nan
    row["violated"] = ";".join(f"{c.id}:{c.margin:+.3f}" for c in failed) if not feasible else ""
    rel = (res.diagnosis or {}).get("relaxations") or []
    row["relaxation"] = _fmt_relaxation(rel[0]) if (rel and diagnose and not feasible) else ""
    notes = [str(n) for n in res.notes]
    nv = {}
    for c in res.not_verified():
        nv.setdefault(c.note.replace("not verified: ", ""), []).append(c.id)
    if nv:
        notes.append(_not_verified_note(nv))
    if res.assumptions():
        notes.append("assumed: " + "; ".join(a.replace(" assumed", "") for a in res.assumptions()))
    if diagnose and not feasible and (res.diagnosis or {}).get("layout"):
        notes.append(res.diagnosis["layout"]["message"])
    row["notes"] = "; ".join(dict.fromkeys(notes))
    return row


def _not_verified_note(groups: dict) -> str:
    """One note for the not-verified checks of a row, grouped by why: ``{why: [constraint ids]}``."""
    return "not verified: " + "; ".join(f"{', '.join(ids)}: {why}" for why, ids in groups.items())


def error_row(exc: Exception) -> dict:
    """The row of an application that cannot be evaluated (its message in ``notes``)."""
    row = {c: math.nan for c in columns()}
    row.update({"feasible": False, "status": "infeasible", "verdict": "fail", "binding_constraint": "", "violated": "",
                "relaxation": "", "notes": f"not evaluated: {exc}".replace("\n", "; ")})
    row.update({f"part_{k}": None for k in PART_KEYS})
    return row


def frame(rows: list) -> pd.DataFrame:
    """The result DataFrame of ``rows`` (dicts of :func:`columns`), index 0..n-1, fixed dtypes."""
    df = pd.DataFrame(rows, columns=columns()) if rows else pd.DataFrame({c: pd.Series(dtype=object) for c in columns()})
    return _dtypes(df)


def _dtypes(df: pd.DataFrame) -> pd.DataFrame:
    df["feasible"] = df["feasible"].astype(bool)
    for c in df.columns:
        if c.startswith(("objective_", "margin_")) or c in ("binding_margin", *CAPABILITY_NUMBERS):
            df[c] = df[c].astype(float)
        elif c in CAPABILITY_COLUMNS:  # text: empty without a target, whichever path built the row
            df[c] = df[c].map(lambda v: "" if v is None or (isinstance(v, float) and math.isnan(v)) else v)
    return df.reset_index(drop=True)


def _settings(settings, fidelity) -> evaluate.Settings:
    """The configuration of a screening: ``settings`` at ``fidelity`` (given: it wins; not given: the settings',
    ``screening`` without settings)."""
    s = settings if settings is not None else evaluate.Settings(fidelity=fidelity or "screening")
    return s if fidelity is None or fidelity == s.fidelity else s.replace(fidelity=fidelity)


def screen_applications_reference(apps: Sequence, *, objective: str = "standard", fidelity: str | None = None,
                                  diagnose: bool = True, settings: evaluate.Settings | None = None) -> pd.DataFrame:
    """Reference engine: ``solve(d, objective, "enumerate", exhaustive=True)`` per application: every core and
    option of its catalog product evaluated, the nearest design and each relaxation probe by the exhaustive
    evaluation (slow; the right answer, and what the fast path is tested against)."""
    settings = _settings(settings, fidelity)
    rows = []
    for d in apps:
        try:
            rows.append(row_from_result(solve(d, with_margin_tiebreak(objective), "enumerate", settings=settings,
                                              relax=diagnose,
                                              exhaustive=True), diagnose))
        except InputError as exc:
            rows.append(error_row(exc))
    return frame(rows)


# --------------------------------------------------------------------------------------------------------------
# the fast path
# --------------------------------------------------------------------------------------------------------------

_CHECKS: dict = {}


def _checks() -> list:
    """The constraints of the bulk row's margin columns (:func:`constraint_ids`), per registry version (a check
    added with ``register`` included)."""
    got = _CHECKS.get(version())
    if got is None:
        got = [REGISTRY[cid] for cid in constraint_ids()]
        _CHECKS.clear()
        _CHECKS[version()] = got
    return got


def _design_attributes(b, rows, options: dict) -> dict:
    """One-row attributes of the chosen designs, as :func:`synth.design.verify.verify` builds them from their part
    keys (the cone spring's outer diameter made absolute and back: the same doubles)."""
    sp = b.sp
    attrs = {"core": sp.rows("core", b.C[rows])}
    for s in ("bushing", "spring", "bolt"):
        attrs[s] = sp.rows(s, options[s])
    ax = sp.rows("axial", options["axial"])
    de_max = b.cg.values["cone_spring_max_external_diameter_mm"][rows]
    spacer = np.asarray(ax["spacer_code"])
    pad = np.asarray(attrs["core"]["pad_code"]) >= 0
    ext = np.where((spacer >= 0) & np.isfinite(de_max), de_max - ax["cone_spring_de_reduction_mm"], 0.0)
    red = np.where(pad, de_max - ext, 0.0)
    attrs["axial"] = axial_attributes(sp.parts, spacer, np.where(spacer >= 0, ax["cone_spring_aspect_ratio"], 0.0),
                                      np.where(spacer >= 0, ax["cone_spring_deflection_ratio"], 0.0),
                                      np.where(spacer >= 0, red, 0.0))
    return attrs


def _verify(b, idx, rows, options: dict) -> dict:
    """Every group of the chosen designs of applications ``idx`` (one call per group for all of them)."""
    attrs = _design_attributes(b, rows, options)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # judged: at full fidelity from screening
        groups = evaluate_design(b.apps, attrs, b.settings, detail=False, of=idx)
    groups["_attrs"] = attrs
    return groups


def _notes_of(apps, idx, state, evaluated, cache: dict) -> list:
    """Per application: the "not verified: ..." and "assumed: ..." notes of its checks (as :func:`row_from_result`
    writes them from the result), built once per distinct pattern of missing requirements and defaults."""
    cols = _checks()
    reqs = sorted({r for c in cols for r in c.needs})
    met = np.stack([apps.met(r)[idx] for r in reqs], axis=1) if reqs else np.zeros((len(idx), 0), bool)
    names = sorted({x for c in cols for x in c.assumes if x in DEFAULTS})
    assumed = np.stack([apps.assumed(x)[idx] for x in names], axis=1) if names else np.zeros((len(idx), 0), bool)
    nv = state == NOT_VERIFIED
    out = []
    for j in range(len(idx)):
        # which fields of an unmet requirement were left out differs between applications
        why_of = {r: apps.missing_note(r, int(idx[j])).replace("not verified: ", "")
                  for k, r in enumerate(reqs) if not met[j, k]} if nv[j].any() else {}
        key = (nv[j].tobytes(), evaluated[j].tobytes(), assumed[j].tobytes(), tuple(why_of.items()))
        hit = cache.get(key)
        if hit is None:
            i = int(idx[j])
            groups: dict = {}
            for c in np.flatnonzero(nv[j]):
                con = cols[c]
                missing = [r for r in con.needs if not met[j, reqs.index(r)]]
                why = why_of[missing[0]] if missing else ""
                groups.setdefault(why, []).append(con.id)
            notes = []
            if groups:
                notes.append(_not_verified_note(groups))
            seen = []
            for c in np.flatnonzero(evaluated[j]):
                for x in cols[c].assumes:
                    if x in DEFAULTS and assumed[j, names.index(x)]:
                        seen.append(apps.assumed_note(x, i))
            seen = list(dict.fromkeys(seen))
            if seen:
                notes.append("assumed: " + "; ".join(a.replace(" assumed", "") for a in seen))
            hit = cache[key] = notes
        out.append(hit)
    return out


def _rows(b, idx, rows, options: dict, groups: dict, status: str, objective) -> dict:
    """The result columns (:func:`columns`, and ``_failed``: the failed constraint ids per row) of designs verified
    by :func:`_verify`, one array or list per column, built column by column: what :func:`row_from_result` gives
    for :func:`synth.optimise.answer.build_result`'s result of each."""
    m = len(idx)
    a = assess(groups, b.apps, app=idx, ids=tuple(c.id for c in _checks()))  # the one judgement of the margins
    marg, ev, failed = a.margins, a.evaluated, a.failed
    # objectives as Evaluation.objective_values sums them
    sp = b.sp
    cv = {k: b.cg.values[k][rows] for k in objectives.core_reads()}
    sc = core_scores(sp, b.C[rows], cv)
    k = b.apps.spring_stiffness_nm_per_deg[idx]
    totals = objectives.additive_totals(sc, [{n: np.zeros(m) + v for n, v in option_scores(
        sp, s, k if s == "spring" else None, options[s]).items()} for s in SUBSYSTEMS])
    ids = a.columns.ids
    feasible = (status == "optimal") & a.ok
    notes_nv = _notes_of(b.apps, idx, a.state, ev, {})
    out = {"feasible": feasible, "status": np.where(feasible, "optimal", "infeasible").astype(object),
           "verdict": a.verdict,
           **{g.column: g.totals(totals[g.name]) if g.additive else a.objective_margin.astype(float)
              for g in objectives.GOALS},
           "margin_min": a.margin_min.astype(float),
           "binding_constraint": a.binding_ids(), "binding_margin": a.binding_margin}
    for key, col in _parts(groups["_attrs"], groups["core"].values).items():
        out[f"part_{key}"] = col
    shown = np.where(ev, marg, np.nan)  # advisory constraints too, as warnings
    for c, cid in enumerate(ids):
        out[f"margin_{cid}"] = shown[:, c]
    failed_ids, violated, notes = [], [], []
    fixed = b.settings.notes()
    for j in range(m):
        fj = np.flatnonzero(failed[j])
        order = fj[np.argsort(marg[j, fj], kind="stable")] if len(fj) else fj
        violated.append(";".join(f"{ids[c]}:{marg[j, c]:+.3f}" for c in order) if not feasible[j] else "")
        nt = b.notes(int(idx[j])) + fixed
        if status in ("optimal", "feasible") and len(fj):
            nt = nt + ["verification failed: " + ", ".join(f"{ids[c]} {marg[j, c]:+.3g}" for c in fj)]
        notes.append("; ".join(dict.fromkeys([str(x) for x in nt] + notes_nv[j])))
        failed_ids.append([ids[c] for c in fj])
    out.update(violated=violated, relaxation=[""] * m, notes=notes, _failed=failed_ids)
    return out


def _parts(attrs: dict, core_values: dict) -> dict:
    """The part columns (:data:`PART_KEYS`) of verified designs: :func:`synth.design.verify.parts_of_rows`."""
    rows = parts_of_rows(attrs, core_values)
    return {k: [r[k] for r in rows] for k in PART_KEYS}


def _screen_chunk(inputs: list, weights: dict, obj, settings, diagnose: bool, margin_ties: bool = False) -> list:
    """The rows of a chunk of applications (see :func:`screen_applications`)."""
    n = len(inputs)
    b = Batch(inputs, settings)
    # ties broken as synth design breaks them (the margin, then catalog order) for a single objective name
    found = b.optimum_margin_ties(weights) if margin_ties else b.optimum(weights)
    bad = [i for i, f in enumerate(found) if f is None]
    near = b.nearest(bad) if bad else [None] * n
    cols = {c: np.empty(n, dtype=object) for c in columns()}
    failed: list = [None] * n
    for status, sel in (("optimal", [i for i in range(n) if found[i] is not None]), ("infeasible", bad)):
        designs = [found[i] if status == "optimal" else near[i] for i in sel]
        if any(d is None for d in designs):  # no core at all: the reference's own answer (or its error)
            raise _NoSpace([i for i, d in zip(sel, designs) if d is None])
        if not sel:
            continue
        idx = np.asarray(sel, dtype=np.int64)
        core_rows = np.array([d[0] for d in designs], dtype=np.int64)
        options = {s: np.array([d[1][s] for d in designs], dtype=np.int64) for s in SUBSYSTEMS}
        groups = _verify(b, idx, core_rows, options)
        part = _rows(b, idx, core_rows, options, groups, status, obj)
        for c in cols:
            cols[c][idx] = part[c] if c in part else None  # the capability columns: empty without a target
        for i, f in zip(sel, part["_failed"]):
            failed[i] = f
    if diagnose and bad:
        rel = relaxations_batch([inputs[i] for i in bad], [failed[i] for i in bad], settings=settings)
        switches = layout_switches([inputs[i] for i in bad], probe_batch(settings))
        for i, r, switch in zip(bad, rel, switches):
            if cols["feasible"][i]:
                continue
            if switch is not None:  # as synth design says it: the switch first, its message in the notes
                r = [switch["relaxation"]] + r
                cols["notes"][i] = "; ".join(x for x in (cols["notes"][i], switch["message"]) if x)
            if r:
                cols["relaxation"][i] = _fmt_relaxation(r[0])
    return cols


def _margin_ties(objective) -> bool:
    """Whether ``synth design`` breaks the ties of ``objective`` by the margin (a single name: ``standard`` is
    ``standard,cost,margin``, :func:`synth.optimise.objectives.with_margin_tiebreak`): the fast path then breaks them
    the same way (:meth:`synth.optimise.batch.Batch.optimum_margin_ties`)."""
    if isinstance(objective, Objective):
        return False
    return Objective.parse(with_margin_tiebreak(objective)).uses_margin() and not Objective.parse(objective).uses_margin()


class _NoSpace(Exception):
    def __init__(self, which):
        super().__init__(f"applications {which} have no core")
        self.which = which


def screen_applications(apps: Sequence, *, objective: str = "standard", fidelity: str | None = None,
                        diagnose: bool = True, settings: evaluate.Settings | None = None) -> pd.DataFrame:
    """One row per application of ``apps`` (validated ``DesignInput``), in the order given (index 0..n-1).

    ``objective`` as :func:`synth.optimise.solve` accepts it; ``fidelity``
    ``screening`` (closed-form wear, linear cone spring) or ``full``;
    ``diagnose=False`` skips the relaxation search of infeasible applications;
    ``settings``: the configuration every row is judged under (:class:`~synth.design.settings.Settings`: design
    rules, spring limit basis, engine; ``fidelity``, when given, sets its fidelity; not given: the settings' own,
    ``screening`` without settings).
    Columns: :func:`columns`. The same answer as :func:`screen_applications_reference`.

    Additive objectives (``standard``, ``cost``, their orders and weighted sums without the margin) take the
    fast path: the chunk on the applications axis (:class:`synth.optimise.batch.Batch`: optimum, nearest
    design), the chosen designs verified together (one call per registry group), the rows assembled from
    the groups, the relaxations of the infeasible ones bisected together
    (:func:`synth.optimise.diagnose.relaxations_batch`). An application whose data a physics function
    refuses (an :class:`~synth.errors.InputError` inside the chunk) is isolated and takes the reference's
    path; objectives with the margin take it too.

    >>> from synth.data.generated_applications import generate
    >>> df = screen_applications(generate(2, seed=0), objective="cost")
    >>> list(df.index), df.loc[1, "status"]
    ([0, 1], 'optimal')
    """
    settings = _settings(settings, fidelity)
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    apps = list(apps)
    if settings.capability is not None:  # each row re-selected for the target: synth design --capability's answer
        from synth.bulk.capability import screen_robust
        return frame(screen_robust(apps, objective, settings, diagnose, lambda a, s: screen_applications(
            a, objective=objective, diagnose=diagnose, settings=s), row_from_result))
    if obj.uses_margin():
        return screen_applications_reference(apps, objective=objective, diagnose=diagnose, settings=settings)
    w = obj.additive_weights() or FALLBACK_WEIGHTS
    ties = _margin_ties(objective)

    def reference_row(d, exc=None):
        return screen_applications_reference([d], objective=objective, diagnose=diagnose,
                                             settings=settings).to_dict(orient="records")[0]

    def reference_frame(d, exc=None):
        row = reference_row(d)
        return _frame({c: np.array([row[c]], dtype=object) for c in columns()})

    def chunk(items):  # a list of pieces (DataFrames), concatenated in order
        try:
            return [_frame(_screen_chunk(items, w, obj, settings, diagnose, ties))]
        except _NoSpace as exc:  # rare: those applications alone, by the reference
            rest = [d for i, d in enumerate(items) if i not in exc.which]
            ok = _frame(_screen_chunk(rest, w, obj, settings, diagnose, ties)) if rest else None
            pieces, k = [], 0
            for i, d in enumerate(items):
                if i in exc.which:
                    pieces.append(reference_frame(d))
                else:
                    pieces.append(ok.iloc[[k]])
                    k += 1
            return [pd.concat(pieces, ignore_index=True)]
    pieces = robust(chunk, apps, reference_frame)
    if len(pieces) == 1:
        return pieces[0]
    whole = pd.concat(pieces, ignore_index=True) if pieces else frame([])
    return _frame({c: whole[c].to_numpy(dtype=object) for c in columns()})  # types inferred on the whole


def _frame(cols: dict) -> pd.DataFrame:
    """The result DataFrame of a chunk's columns (:func:`_screen_chunk`), typed as :func:`frame` types rows."""
    # from lists, as from rows: the same inference (text, numbers with None as NaN)
    return _dtypes(pd.DataFrame({c: list(cols[c]) for c in columns()}, columns=columns()))

