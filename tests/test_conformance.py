"""The conformance matrix (issue 33), generated from the registry as scikit-learn's ``parametrize_with_checks``
generates the common checks of every estimator: every evaluated group x what its check reads (a value of its own
group, an application field, a value of its core) x engine (compiled, numpy) x configuration (no rules, design
rules, the EN 13906 spring limit basis) x path (flowchart, ``synthesise``, ``screen``, bulk, platform, robust)
gives the same margin. A check that reads another part family's value (read kind "other") is refused alike by
every path (:class:`synth.errors.DeclarationError` naming it): each family is chosen apart from the others given
its core, so no path can hand it that value; before, a bolt check reading the main spring's mean diameter read
the application's pin of it (NaN when the search chooses the spring) and failed every design with margin -inf.

Each cell registers a probe check (:func:`probe`): its physics reads one key, by name, and returns ``value = a`` and
``limit = a / (1 - M)`` with ``a = |key| + 1``, so its margin is ``M`` on every row of every path that evaluates it,
and ``M - REQUIRED`` under the design rules, whose ``min_margins`` name every probe (the probe's value never
matters; that it is read, through the path's own plumbing, does). A path that cannot hand the key to the physics
raises (before issue 33 a core value read by a non-core group raised ``KeyError``, an application field read by a
spring check ``AttributeError``); a path that drops the rules shows ``M``, not ``M - REQUIRED``. Besides the probes,
every path's design must carry the margins the one evaluator gives it under the same configuration
(:func:`synth.verify`: the spring limit basis and the rules' real checks included), and the platform's feasible
options and margins must be the optimiser's catalog product's (:func:`synth.optimise.product.evaluate`).

The rules also tighten real spring checks (a coil-gap margin, the Goodman safety factor), and the limit basis changes
the yield check: where that is so the compiled spring kernels must give way to their numpy twin
(:func:`synth.kernels.engines.spring`), or the margins differ from the one evaluator's. The probes of the spring
group are registered apart from the others (with a spring probe registered the compiled kernels never run), so
the compiled column runs the compiled spring kernels wherever the configuration allows them.

Every run is made once per (registration, engine, configuration, path) and read by its cells; the flowchart and
the robust path evaluate with the numpy reference whatever the engine (they evaluate designs, no search of many
rows), so their numpy run answers both engine columns.
"""

from __future__ import annotations

import inspect

import numpy as np
import pytest

import synth
from synth.data.generated_applications import generate
from synth.design.constraints import EVALUATED_GROUPS, Constraint, by_group, registered
from synth.design.evaluate import core_values
from synth.design.settings import Settings
from synth.design.space import PART_KEYS, PART_KEYS_BY_TABLE, SUBSYSTEMS
from synth.errors import DeclarationError
from synth.schema import FIELDS

#: the probe's margin without rules, and the margin the design rules ask every probe to keep
M, REQUIRED = 0.02, 0.005
#: the application field every probe of kind "application" reads (a required input: every application gives it)
APPLICATION_FIELD = "spring_stiffness_nm_per_deg"
#: core values a probe of kind "core" reads: the first its group's function does not read already
CORE_CANDIDATES = ("pivot_diameter_mm", "bearing_width_mm")
ENGINES = ("numba", "numpy")
PATHS = ("flowchart", "synthesise", "screen", "bulk", "platform", "robust")
#: paths whose physics never takes the engine (designs evaluated one by one, the numpy reference)
ENGINE_FREE = ("flowchart", "robust")


def _declared(group: str) -> tuple:
    return core_values(group, ()) if group in SUBSYSTEMS else ()


def key_of(group: str, read: str) -> str | None:
    """The key a probe of ``group`` reads: its group's first check's value (``own``), :data:`APPLICATION_FIELD`
    (``application``), a core value its group's function does not read (``core``; None for the input and core
    groups, whose own values are the core's)."""
    if read == "own":
        return by_group(group)[0].value
    if read == "application":
        return APPLICATION_FIELD
    if read == "other":  # another family's part: first an input field that pins one (numeric), else its part key
        pins = [f.name for f in FIELDS if f.pins and f.pins[0] in SUBSYSTEMS and f.pins[0] != group
                and f.kind == "float"]
        return (pins + [k for t in SUBSYSTEMS if t != group for k in PART_KEYS_BY_TABLE[t]])[0]
    if group in ("input", "core"):
        return None
    return next(k for k in CORE_CANDIDATES if k not in _declared(group))


#: the matrix's rows: every evaluated group x every kind of read it has (generated from the registry's groups)
CELLS = [(g, r) for g in EVALUATED_GROUPS for r in ("own", "application", "core") if key_of(g, r)]


def probe_id(group: str, read: str) -> str:
    return f"conformance_{group}_{read}"


def probe(group: str, read: str) -> Constraint:
    """The check of cell (``group``, ``read``): margin :data:`M` wherever its group is evaluated."""
    key, cid = key_of(group, read), probe_id(group, read)

    def physics(**kw):
        a = np.abs(np.nan_to_num(np.asarray(kw[key], dtype=float), nan=0.0, posinf=0.0, neginf=0.0)) + 1.0
        return {f"{cid}_value": a, f"{cid}_limit": a / (1.0 - M)}
    physics.__signature__ = inspect.Signature([inspect.Parameter(key, inspect.Parameter.KEYWORD_ONLY)])
    return Constraint(id=cid, label=f"conformance probe: the {group} group reads {key}", step=0, equation="test",
                      unit="-", group=group, value=f"{cid}_value", limit=f"{cid}_limit", sense="<=", physics=physics)


#: the probes registered together: the spring group's apart (with one registered the compiled kernels never run)
REGISTRATIONS = {"spring": [c for c in CELLS if c[0] == "spring"], "others": [c for c in CELLS if c[0] != "spring"]}


def registration_of(group: str) -> str:
    return "spring" if group == "spring" else "others"


def configs(registration: str) -> dict:
    """The configurations (made while the registration's probes are registered): none, design rules (every probe
    but the input group's keeps :data:`REQUIRED`: a rule asks no margin of an input-only check; a coil-gap margin
    and a higher Goodman safety factor on the real spring checks), the EN 13906 limit basis."""
    ids = [probe_id(g, r) for g, r in REGISTRATIONS[registration] if g != "input"]
    rules = {"name": "conformance rules", "min_margins": {**{i: REQUIRED for i in ids}, "spring_coil_gap": 0.05},
             "limits": {"main_spring_min_safety_factor": 1.25}}
    return {"no rules": {}, "rules": {"rules": rules}, "spring_limit_basis": {"spring_limit_basis": "en13906"}}


CONFIGS = ("no rules", "rules", "spring_limit_basis")


def expected(group: str, config: str) -> float:
    return M - REQUIRED if config == "rules" and group != "input" else M


@pytest.fixture(scope="module")
def apps():
    """Two generated applications, feasible in every configuration: one with the axial damping group and its
    durability test (the cone spring and the wear are evaluated), one without."""
    pool = generate(14, seed=11)
    return [pool[i] for i in APPS]


APPS = (4, 13)


# --------------------------------------------------------------------------------------------------------- the paths
def _row(margins: dict, parts: dict | None) -> dict:
    return {"margins": {k: float(v) for k, v in margins.items() if v is not None and np.isfinite(v)}, "parts": parts}


def _flowchart(apps, kw):
    return [_row(r.margins, r.parts or None) for r in (synth.run_flowchart(d, **kw) for d in apps)]


def _synthesise(apps, kw):
    return [_row(r.margins, r.parts or None) for r in (synth.synthesise(d, **kw) for d in apps)]


def _frame_rows(df) -> list:
    out = []
    for _, row in df.iterrows():
        margins = {c[len("margin_"):]: row[c] for c in df.columns if c.startswith("margin_") and c != "margin_min"}
        parts = {k: row[f"part_{k}"] for k in PART_KEYS} if row["status"] == "optimal" else None
        out.append(_row({k: v for k, v in margins.items() if v == v}, parts))
    return out


def _screen(apps, kw):
    return _frame_rows(synth.screen(apps, diagnose=False, progress=False, **kw))


def _bulk(apps, kw, tmp):
    from synth.bulk.portfolio import write_table
    from synth.bulk.run import run_portfolio
    import dataclasses
    import pandas as pd
    table = pd.DataFrame([{k: v for k, v in dataclasses.asdict(d).items() if v is not None} for d in apps])
    path = write_table(table, tmp / "portfolio.csv")
    s = synth.settings(fidelity="screening", **kw)
    rep = run_portfolio(path, tmp / "result.csv", diagnose=False, settings=s)
    return _frame_rows(rep.table)


def _platform(apps, kw):
    """The producer's feasibility data, each application's options against the optimiser's catalog product under
    the same configuration (feasible sets and margins), and per subsystem the largest option margin (the probes
    of its group cap it)."""
    from synth.optimise.product import evaluate
    from synth.platform.options import catalogue
    from synth.platform.producer import MARGIN_TOL
    from synth.platform.portfolio_feasibility import feasibility
    s = synth.settings(**kw)
    pf = feasibility(apps, settings=s)
    cat = catalogue()
    out = []
    for a, d in zip(pf.apps, apps):
        ev = evaluate(d, s)
        cores = ev.cores[ev.rows]
        assert sorted(a.core_rows.tolist()) == sorted(cores.tolist())
        best = {"core": float(np.max(a.core_margin)) if len(a.core_margin) else None}
        for r_idx, row in enumerate(cores):
            c = int(np.flatnonzero(a.core_rows == row)[0])
            assert a.core_margin[c] == ev.core.min_margin()[ev.rows[r_idx]]
            for sub in SUBSYSTEMS:
                g = int(a.group[sub][c])
                mine = dict(zip([int(cat.option_row[sub][int(o)]) for o in a.feasible[sub][g]], a.option_margin[sub][g]))
                theirs = np.flatnonzero(ev.subs[sub].feasible[r_idx])
                assert set(mine) == set(theirs.tolist()), (sub, int(row))
                for k in theirs:
                    tol = MARGIN_TOL if sub == "axial" else 0.0
                    assert abs(mine[int(k)] - ev.subs[sub].margin[r_idx, k]) <= tol, (sub, int(row), int(k))
                if mine:
                    best[sub] = max(best.get(sub) or -np.inf, max(mine.values()))
        out.append({"best": best, "complete": a.n_cores and not a.note})
    return out


def _robust(apps, kw):
    """``synth robust``'s capability of each synthesised design, under the configuration the result carries
    (:meth:`synth.design.settings.Settings.from_saved`, as the robust scene and the report read a result): the
    nominal margin of every check it samples."""
    from synth.robust.capability import capability
    from synth.robust.sampling import base_of
    from synth.robust.settings import RobustSettings
    out = []
    for d in apps:
        r = synth.synthesise(d, **kw)
        cap = capability(base_of(d, r.parts, Settings.from_saved(r.settings, r.rules)), RobustSettings(samples=64),
                         rare=False, details=False)
        out.append(_row({c.id: c.nominal for c in cap.checks}, r.parts))
    return out


RUNS: dict = {}


def run(path: str, registration: str, engine: str, config: str, apps, tmp_path_factory):
    """The rows of ``path`` for ``apps`` under (``registration``, ``engine``, ``config``), made once."""
    if path in ENGINE_FREE:
        engine = "numpy"
    key = (path, registration, engine, config)
    if key not in RUNS:
        with registered(*(probe(g, r) for g, r in REGISTRATIONS[registration])):
            kw = {"engine": engine, **configs(registration)[config]}
            if path == "bulk":
                RUNS[key] = _bulk(apps, kw, tmp_path_factory.mktemp("bulk"))
            else:
                RUNS[key] = {"flowchart": _flowchart, "synthesise": _synthesise, "screen": _screen,
                             "platform": _platform, "robust": _robust}[path](apps, kw)
            if path != "platform":  # every design's margins are the one evaluator's under the same configuration
                # the robust path judges the made tensioner: the made joint of VDI 2230 (issue 34,
                # synth.robust.sampling.production), the rest of the configuration as given
                made = {"bolt_method": "vdi2230"} if path == "robust" else {}
                for d, row in zip(apps, RUNS[key]):
                    if row["parts"]:
                        want = synth.verify(d, row["parts"], **{**configs(registration)[config], **made}).margins
                        for cid, m in row["margins"].items():
                            if cid in want:
                                assert m == pytest.approx(want[cid], rel=1e-12, abs=1e-12), (path, cid)
        if engine == "numba":  # the compiled engine's answers are the numpy reference's: the same designs, margins
            ref = run(path, registration, "numpy", config, apps, tmp_path_factory)
            for mine, theirs in zip(RUNS[key], ref):
                if path == "platform":
                    assert mine["best"].keys() == theirs["best"].keys()
                    for k, v in mine["best"].items():
                        assert (v is None and theirs["best"][k] is None) or abs(v - theirs["best"][k]) <= 1e-9, k
                    continue
                assert mine["parts"] == theirs["parts"], path
                assert mine["margins"].keys() == theirs["margins"].keys(), path
                for cid, m in mine["margins"].items():
                    assert m == pytest.approx(theirs["margins"][cid], rel=1e-9, abs=1e-12), (path, cid)
    return RUNS[key]


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("group", EVALUATED_GROUPS)
def test_another_part_family_value_is_refused_by_every_path(group, path, apps, tmp_path_factory):
    """Read kind "other": every path stops with the one :class:`DeclarationError` naming the check and the value,
    never a margin (nor a ``KeyError``, nor a row marked infeasible)."""
    key, cid = key_of(group, "other"), probe_id(group, "other")
    with registered(probe(group, "other")):
        with pytest.raises(DeclarationError, match=f"constraint {cid} .*{key}"):
            if path == "bulk":
                _bulk(apps[:1], {}, tmp_path_factory.mktemp("bulk"))
            else:
                {"flowchart": _flowchart, "synthesise": _synthesise, "screen": _screen, "platform": _platform,
                 "robust": _robust}[path](apps[:1], {})


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("config", CONFIGS)
@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("group, read", CELLS, ids=[f"{g}-{r}" for g, r in CELLS])
def test_conformance(group, read, engine, config, path, apps, tmp_path_factory):
    rows = run(path, registration_of(group), engine, config, apps, tmp_path_factory)
    want = expected(group, config)
    cid = probe_id(group, read)
    if path == "platform":
        if group in ("input",):
            pytest.skip("the producer judges the input-only checks as the core's feasibility")  # noqa
        for row in rows:
            best = row["best"].get(group)
            if best is not None:
                assert best <= want + 1e-12
        return
    for row in rows:
        assert row["margins"][cid] == pytest.approx(want, rel=1e-12, abs=1e-12)
