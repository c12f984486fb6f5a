"""Every assigned design checked again, whole, through :func:`synth.design.verify.verify`.

A platform's assignment (:func:`synth.platform.assign.assign`) picks, per application,
a core and one option per subsystem from the feasibility data. On real data
(:mod:`synth.platform.producer`) each choice is a row of the design space, so the
design can be rebuilt with the part keys every result uses
(:data:`synth.design.space.PART_KEYS`, :func:`design_parts`) and verified on its own
(:func:`verify_records`): its verdict, smallest margin and binding constraint in
``assignment.csv`` are those of the :class:`~synth.design.result.Result`, and a
design that failed would be reported as not served (it does not happen: the data come
from the same group functions; the tests check it on 200 applications).

:func:`verify_records` is :func:`synth.design.verify.verify` on the applications axis:
the attributes come from the part keys (:meth:`synth.design.space.Space.design_attributes`,
as ``verify`` builds them), every group is evaluated once for all the designs
(:func:`synth.design.verify.evaluate_design` with one row per design) and each row's checks are :func:`synth.design.result.checks_of`. The tests
hold it equal to ``verify`` design by design (verdicts, margins, binding constraint);
it is 20x faster (one bolt step-10 evaluation per bolt, not per design).

>>> from synth.data.generated_applications import generate
>>> from synth.platform.portfolio_feasibility import feasibility
>>> from synth.platform.assign import assign, full_platform
>>> pf = feasibility(generate(2, seed=0), ["a", "b"])
>>> recs = verify_records(pf, assign(pf, full_platform(pf)))
>>> [(r["app_id"], r["feasible"], r.get("verdict")) for r in recs]
[('a', False, None), ('b', True, 'incomplete')]
"""

from __future__ import annotations

import numpy as np

from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.assessment import assess
from synth.design.space import SUBSYSTEMS
from synth.design.result import Result, checks_of
from synth.design.verify import evaluate_design, parts_of_rows

__all__ = ["design_parts", "verify_records"]


def design_parts(pf, items: list) -> list:
    """The part keys (:data:`~synth.design.space.PART_KEYS`) of each ``(application i, core, {subsystem: option})``
    of ``items`` (the cores and options of :class:`~synth.platform.data.AppFeasibility` and of ``pf``'s tables)."""
    if not items:
        return []
    cat = pf.catalogue
    sp = cat.space
    rows = {"core": np.array([int(pf.apps[i].core_rows[c]) for i, c, _ in items])}
    for s in SUBSYSTEMS:
        rows[s] = np.array([int(cat.option_row[s][int(o[s])]) for _, _, o in items])
    attrs = {t: sp.rows(t, r) for t, r in rows.items()}
    apps = Applications.of([pf.design_inputs[i] for i, _, _ in items])
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        cg = evaluate.core(apps, np.arange(len(items)), attrs["core"], pf.settings or evaluate.Settings())
    return parts_of_rows(attrs, cg.values)


def verify_records(pf, records: list) -> list:
    """Verify every feasible record of ``records`` (in place; returned): ``design`` (the part keys),
    ``verdict`` (``pass`` or ``incomplete``), ``margin`` and ``binding`` from the verified result.

    A design the verification fails is marked not served with the failed checks as its reason. Data without
    design inputs (:mod:`synth.platform.synthetic`) are returned unchanged.
    """
    if pf.design_inputs is None or pf.catalogue is None:
        return records
    settings = pf.settings or evaluate.Settings()
    todo = [i for i, r in enumerate(records) if r["feasible"]]
    if not todo:
        return records
    sp = pf.catalogue.space
    parts = design_parts(pf, [(i, records[i]["core"], records[i]["options"]) for i in todo])
    memo: dict = {}   # a platform's designs repeat (1,000 applications: 713 designs, 143 distinct): each built once
    one = [memo[k] if k in memo else memo.setdefault(k, sp.design_attributes(p))
           for k, p in ((tuple(sorted(p.items())), p) for p in parts)]
    attrs = {t: {k: np.concatenate([np.asarray(x[t][k]) for x in one]) for k in one[0][t]} for t in one[0]}
    apps = Applications.of([pf.design_inputs[i] for i in todo])
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        groups = evaluate_design(apps, attrs, settings, detail=False)
    judged = assess(groups, apps)  # every design's assessment at once; each row's checks read it
    for row, (i, p) in enumerate(zip(todo, parts)):
        rec = records[i]
        res = Result(status="verified", parts=p, checks=checks_of(groups, apps, row, judged))
        rec["design"] = p
        rec["verdict"] = res.verdict
        failed = res.failed()
        if failed:
            rec.update(feasible=False, reason="verification failed: " + ", ".join(
                f"{c.id} ({c.margin:+.3f})" for c in failed))
            continue
        bind = res.binding(1)
        if bind:
            rec["margin"], rec["binding"] = float(bind[0].margin), bind[0].id
    return records
