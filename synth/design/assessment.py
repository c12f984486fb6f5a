"""The one assessment of designs: the registry's margins judged once, on arrays (issue 21).

The evaluator (:mod:`synth.design.evaluate`) gives each group's margins and
states; :func:`assess` stacks the groups of designs into ``(n, k)`` arrays over
the registry's columns (registry order) and derives, once for every consumer,
what a design's margins mean:

* per check: ``evaluated``, ``not_verified``, ``failed`` (a non-advisory
  margin below ``-FEAS_TOL``), ``warning`` (an advisory one), ``counted`` (the
  evaluated non-advisory checks: feasibility and the smallest margin),
  ``binding_candidates`` (counted and ``objective``) and ``in_objective``
  (counted in the margin objective: :meth:`Constraint.counts_in_objective`),
  ``assumed`` (an evaluated check used a documented default);
* per design: ``ok``, ``margin_min``, ``objective_margin``, ``binding`` (the
  most violated check when one fails, the first of ties; else the smallest
  binding candidate), ``incomplete`` and ``verdict`` (fail, incomplete, pass).

``Group.ok`` / ``Group.min_margin``, :func:`synth.design.result.checks_of`,
:class:`~synth.design.result.Result` (from its checks: :meth:`Assessment.of_checks`,
a saved result has no groups), the optimisers' margin objective, the
platform's producer, the bulk rows and the capability targets all read it: the
rules below are written once; :func:`verdict_of` is shared with the per-check
records of a saved result.

>>> import numpy as np
>>> from synth.design.evaluate import Group
>>> g = Group("bushing", {"app": np.zeros(2, int)},
...           {"bushing_p": np.array([0.3, -0.2]), "bushing_wear": np.array([0.1, np.inf])},
...           {"bushing_p": np.zeros(2, np.int8), "bushing_wear": np.array([0, NOT_VERIFIED_STATE], np.int8)})
>>> a = assess({"bushing": g})
>>> a.ok.tolist(), a.margin_min.tolist(), a.verdict.tolist(), a.binding_ids().tolist()
([True, False], [0.1, -0.2], ['pass', 'fail'], ['bushing_wear', 'bushing_p'])
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from synth.design.combine import near_figures
from synth.design.constraints import FEAS_TOL, GROUPS, REGISTRY, version
from synth.design.applications import DEFAULTS

__all__ = ["Assessment", "Columns", "assess", "assess_group", "columns_of", "verdict_of", "passes", "check_verdict",
           "EVALUATED", "NOT_APPLICABLE", "NOT_VERIFIED_STATE", "PASS", "FAIL", "INCOMPLETE", "NOT_VERIFIED",
           "NOT_APPLICABLE_VERDICT", "WARNING", "EVALUATED_VERDICTS"]

#: a check's state in a group (:attr:`synth.design.evaluate.Group.state`)
EVALUATED, NOT_APPLICABLE, NOT_VERIFIED_STATE = 0, 1, 2
#: a design's verdicts, and a check's
PASS, FAIL, INCOMPLETE = "pass", "fail", "incomplete"
NOT_VERIFIED, NOT_APPLICABLE_VERDICT, WARNING = "not verified", "not applicable", "warning"
#: the verdicts of a check that was evaluated (it has a margin)
EVALUATED_VERDICTS = (PASS, FAIL, WARNING)


def verdict_of(failed, incomplete):
    """A design's verdict: ``fail`` where a check fails, else ``incomplete`` where a check was not verified or used a
    documented default, else ``pass`` (scalars give a ``str``, arrays an object array).

    >>> verdict_of(False, True), verdict_of(np.array([True, False]), np.array([True, False])).tolist()
    ('incomplete', ['fail', 'pass'])
    """
    out = np.where(failed, FAIL, np.where(incomplete, INCOMPLETE, PASS)).astype(object)
    return out.item() if out.ndim == 0 else out


def check_verdict(c, margin: float) -> str:
    """The verdict of one evaluated check of constraint ``c`` at ``margin``: ``pass`` where it passes
    (:func:`passes`), else ``warning`` for an advisory constraint and ``fail`` for the others; the checks a scene
    computes apart from the evaluator's groups (the shrink fit) are judged by it too.

    >>> check_verdict(REGISTRY["spring_yield"], -1e-12), check_verdict(REGISTRY["spring_yield"], -0.01)
    ('pass', 'fail')
    """
    return PASS if bool(passes(margin)) else (WARNING if c.advisory else FAIL)


@dataclass(frozen=True)
class Columns:
    """The registry columns of an assessment and their static flags (``(k,)`` arrays, and column lists)."""

    constraints: tuple
    ids: np.ndarray
    advisory: np.ndarray
    #: counted in the margin objective unless ``objective_unless`` says otherwise: ``objective`` and not advisory
    objective: np.ndarray
    #: the registry position of each column (:data:`REGISTRY` order)
    index: np.ndarray
    #: ``(column, value key)`` of the objective checks with an ``objective_unless`` value
    unless: tuple
    #: the columns of the non-advisory checks, and of the objective ones (lists, for the per-design reductions)
    decisive: tuple
    objective_columns: tuple
    #: the checks that depend on the design (:attr:`Constraint.design`)
    design: np.ndarray
    #: targeted by the production capability outside the margin objective (:attr:`Constraint.capability`)
    capability: np.ndarray


_COLUMNS: dict = {}


def columns_of(ids: tuple) -> Columns:
    """The :class:`Columns` of constraint ``ids`` (cached per registry version)."""
    key = (version(), ids)
    got = _COLUMNS.get(key)
    if got is None:
        if len(_COLUMNS) > 64:
            _COLUMNS.clear()
        cons = tuple(REGISTRY[i] for i in ids)
        pos = {c: i for i, c in enumerate(REGISTRY)}
        objective = np.array([c.counts_in_objective({}) for c in cons], dtype=bool)  # no objective_unless value
        got = _COLUMNS[key] = Columns(
            cons, np.array(ids, dtype=object), np.array([c.advisory for c in cons], dtype=bool), objective,
            np.array([pos[i] for i in ids], dtype=np.int64),
            tuple((j, c.objective_unless) for j, c in enumerate(cons) if objective[j] and c.objective_unless),
            tuple(j for j, c in enumerate(cons) if not c.advisory), tuple(np.flatnonzero(objective).tolist()),
            np.array([c.design for c in cons], dtype=bool),
            np.array([c.capability and not c.advisory for c in cons], dtype=bool))
    return got


class Assessment:
    """The judgement of ``n`` designs over ``k`` registry columns (see the module docstring).

    Built from the columns' ``(n,)`` margins and states (:func:`assess`, :meth:`of_checks`): a margin is ``+inf``
    where its check does not apply or is not verified (the evaluator's contract, :func:`synth.design.evaluate.finish`),
    ``-inf`` where its value is NaN; a state :data:`EVALUATED`, :data:`NOT_APPLICABLE` or
    :data:`NOT_VERIFIED_STATE` (None: evaluated, a compiled kernel's group; the list, or a function giving it); ``unless``: per objective column with
    an ``objective_unless`` value, its ``(n,)`` values (positive: the design meets the check by construction, it
    leaves the margin objective); ``assumed`` ``(n, k)`` or None (no applications).

    The ``(n, k)`` arrays (:attr:`margins`, :attr:`state` and the masks) are stacked on first use; the per-design
    vectors that read only margins (:attr:`ok`, :attr:`margin_min`, :attr:`objective_margin`) reduce the columns
    without stacking them (the optimisers call them in their inner loops).
    """

    def __init__(self, columns: Columns, margin_columns: list, state_columns, unless: dict,
                 assumed: np.ndarray | None = None, n: int = 0):
        self.columns, self._m, self._s = columns, margin_columns, state_columns
        self.unless, self.assumed = unless, assumed
        self.n = len(margin_columns[0]) if margin_columns else n

    def __len__(self) -> int:
        return self.n

    # --- (n, k) arrays -----------------------------------------------------------------------------------------
    @cached_property
    def margins(self) -> np.ndarray:
        """``(n, k)`` the margins (a transposed view of the stacked columns)."""
        return (np.stack(self._m) if self._m else np.zeros((0, self.n))).T

    @cached_property
    def state(self) -> np.ndarray:
        """``(n, k)`` the states."""
        states = self._s() if callable(self._s) else self._s  # a group's states are gathered on first use
        cols = [np.zeros(self.n, np.int8) if s is None else s for s in states]
        return (np.stack(cols) if cols else np.zeros((0, self.n), np.int8)).T

    @cached_property
    def evaluated(self) -> np.ndarray:
        return self.state == EVALUATED

    @cached_property
    def not_verified(self) -> np.ndarray:
        return self.state == NOT_VERIFIED_STATE

    @cached_property
    def below(self) -> np.ndarray:
        """Checks whose margin is below ``-FEAS_TOL`` (round-off of equal values passes; a check not evaluated has
        ``+inf``): ``failed``, or a ``warning`` for an advisory check (the thesis's Table 7 ranges never fail a design)."""
        return ~passes(self.margins)

    @cached_property
    def failed(self) -> np.ndarray:
        return self.below & ~self.columns.advisory

    @cached_property
    def warning(self) -> np.ndarray:
        return self.below & self.columns.advisory

    @cached_property
    def counted(self) -> np.ndarray:
        """The evaluated non-advisory checks: what feasibility and the smallest margin read."""
        return self.evaluated & ~self.columns.advisory

    @cached_property
    def binding_candidates(self) -> np.ndarray:
        """Counted checks of the margin objective (``objective``), whatever their ``objective_unless``."""
        return self.evaluated & self.columns.objective

    @cached_property
    def counts_in_objective(self) -> np.ndarray:
        """``(n, k)`` :meth:`Constraint.counts_in_objective` of each column, evaluated or not."""
        out = np.broadcast_to(self.columns.objective, (self.n, len(self.columns.ids)))
        if self.unless:
            out = out.copy()
            for j in self.unless:
                out[:, j] &= self._counts(j)
        return out

    @cached_property
    def targeted(self) -> np.ndarray:
        """``(n, k)`` the checks a production capability targets (:mod:`synth.robust`): those counted in the margin
        objective (:attr:`counts_in_objective`), and those the registry targets at their made scatter although the
        margin objective leaves them out (:attr:`Constraint.capability`: the safety factors a preload is sized
        to), that depend on the design."""
        return (self.counts_in_objective | self.columns.capability) & self.columns.design

    @cached_property
    def in_objective(self) -> np.ndarray:
        """The counted checks of the margin objective (:meth:`Constraint.counts_in_objective`)."""
        return self.evaluated & self.counts_in_objective

    # --- per design --------------------------------------------------------------------------------------------
    def _counts(self, j: int) -> np.ndarray:
        """``(n,)`` where column ``j`` counts in the margin objective given its ``objective_unless`` values (the
        registry's rule, :meth:`Constraint.counts_in_objective`)."""
        c = self.columns.constraints[j]
        return np.broadcast_to(c.counts_in_objective({c.objective_unless: self.unless[j]}), (self.n,))

    def _objective_column(self, j: int) -> np.ndarray:
        """Column ``j``'s margins where it counts in the margin objective, ``+inf`` elsewhere."""
        m = self._m[j]
        return np.where(self._counts(j), m, np.inf) if j in self.unless else m

    def _least(self, cols) -> np.ndarray:
        out = np.full(self.n, np.inf)
        for m in cols:
            np.minimum(out, m, out=out)
        return out

    @cached_property
    def ok(self) -> np.ndarray:
        """``(n,)`` no check fails (:attr:`failed`; not verified and not applicable ones have ``+inf``)."""
        out = np.ones(self.n, dtype=bool)
        for j in self.columns.decisive:
            out &= passes(self._m[j])
        return out

    @property
    def any_failed(self) -> np.ndarray:
        return ~self.ok

    @cached_property
    def margin_min(self) -> np.ndarray:
        """``(n,)`` the smallest margin of the counted (non-advisory) checks."""
        return self._least(self._m[j] for j in self.columns.decisive)

    @cached_property
    def near(self) -> tuple:
        """``((n,) smallest, (n,) second smallest, (n,) number failing)`` of the counted checks: the near figures
        that rank nearest designs (:func:`synth.design.combine.near_figures`)."""
        cols = [self._m[j] for j in self.columns.decisive]
        return near_figures(np.stack(cols, axis=1) if cols else np.full((self.n, 0), np.inf))

    @cached_property
    def objective_margin(self) -> np.ndarray:
        """``(n,)`` the margin objective: the smallest margin of the checks counted in it."""
        return self._least(self._objective_column(j) for j in self.columns.objective_columns)

    def smallest(self, mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``((n,) smallest margin, (n,) its column)`` over the checks ``mask`` (the first of ties, a check of
        ``mask`` when all its margins are ``+inf``; ``+inf`` and column 0 where ``mask`` holds none)."""
        if not len(self.columns.ids):
            return np.full(self.n, np.inf), np.zeros(self.n, np.int64)
        m = np.where(mask, self.margins, np.inf)
        col = m.argmin(axis=1)
        best = np.take_along_axis(m, col[:, None], axis=1)[:, 0]
        return best, np.where(np.isposinf(best), np.argmax(mask, axis=1), col)

    @cached_property
    def binding(self) -> np.ndarray:
        """``(n,)`` the binding column: the most violated check when one fails (first of ties), else the smallest
        margin of the binding candidates (meaningful where :attr:`has_binding`)."""
        worst = self.smallest(self.failed)[1]
        least = self.smallest(self.binding_candidates)[1]
        return np.where(self.any_failed, worst, least)

    @cached_property
    def has_binding(self) -> np.ndarray:
        return self.any_failed | self.binding_candidates.any(axis=1)

    def binding_ids(self) -> np.ndarray:
        """``(n,)`` the binding constraint id ("" where none)."""
        ids = self.columns.ids[self.binding] if len(self.columns.ids) else np.full(self.n, "", dtype=object)
        return np.where(self.has_binding, ids, "").astype(object)

    @cached_property
    def binding_margin(self) -> np.ndarray:
        """``(n,)`` the margin of the binding check (``+inf`` where none)."""
        if not len(self.columns.ids):
            return np.full(self.n, np.inf)
        m = np.take_along_axis(self.margins, self.binding[:, None], axis=1)[:, 0]
        return np.where(self.has_binding, m, np.inf)

    def objective_binding(self, objective_only: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """``((n,) margin, (n,) registry index)`` of the smallest margin counted in the margin objective (or of every
        counted check), the index -1 where that margin is ``+inf`` (none counts)."""
        m, col = self.smallest(self.in_objective if objective_only else self.counted)
        return m, np.where(np.isposinf(m), -1, self.columns.index[col] if len(self.columns.ids) else -1)

    @cached_property
    def incomplete(self) -> np.ndarray:
        """``(n,)`` a check was not verified (missing optional data) or used a documented default."""
        out = self.not_verified.any(axis=1)
        if self.assumed is not None:
            out = out | self.assumed.any(axis=1)
        return out

    @cached_property
    def verdict(self) -> np.ndarray:
        """``(n,)`` ``fail``, ``incomplete`` or ``pass`` (:func:`verdict_of`)."""
        return verdict_of(self.any_failed, self.incomplete)

    # --- from records ------------------------------------------------------------------------------------------
    @classmethod
    def of_checks(cls, checks: list, values: dict) -> "Assessment":
        """The one-design assessment of :class:`~synth.design.result.Check` records (a result, saved or not) and
        its ``values`` (for ``objective_unless``): a check evaluated where its verdict is pass, fail or warning, a
        missing margin ``-inf`` if it failed, ``+inf`` otherwise (so :attr:`failed` is the fail verdicts)."""
        cols = columns_of(tuple(c.id for c in checks))
        m, st = [], []
        for c in checks:
            ev = c.verdict in EVALUATED_VERDICTS
            st.append(np.array([EVALUATED if ev else (NOT_APPLICABLE if c.verdict == NOT_APPLICABLE_VERDICT
                                                      else NOT_VERIFIED_STATE)], np.int8))
            m.append(np.array([(c.margin if c.margin is not None else (-np.inf if c.verdict == FAIL else np.inf))
                               if ev else np.inf], dtype=float))
        unless = {j: np.array([np.nan if values.get(k) is None else values[k]], dtype=float)
                  for j, k in cols.unless if k in values}
        return cls(cols, m, st, unless, n=1)


def passes(margin) -> np.ndarray:
    """Where a margin passes: at least ``-FEAS_TOL`` (round-off of equal values; NaN never passes). The one pass
    rule: the assessment, the flowchart's choices, the searches and the capability counts read it.

    >>> passes(np.array([0.0, -1e-12, -1e-6, np.nan])).tolist()
    [True, True, False, False]
    """
    return margin >= -FEAS_TOL


def _take(x, rows):
    x = np.asarray(x)
    return x if rows is None else x[rows]


def assess(groups: dict, apps=None, rows=None, app=None, ids=None) -> Assessment:
    """The assessment of the designs whose evaluated groups are ``groups`` (``{name: Group}``, row ``i`` of every
    group one design; keys that are not registry groups ignored), over the registry's constraints of those
    groups (registry order), for rows ``rows`` (default all).

    ``apps`` (optional :class:`~synth.design.applications.Applications`): the ``assumed`` checks (an evaluated
    check whose :attr:`~Constraint.assumes` input took its documented default); ``app``: the application of each
    row (default: each group's ``app`` values; row ``i`` is application ``i`` in a group without them); ``ids``:
    the constraints to assess, in that order (default: every registry constraint the groups hold).
    """
    gs = {k: g for k, g in groups.items() if k in GROUPS}
    if ids is None:
        ids = tuple(cid for cid, c in REGISTRY.items() if c.group in gs and cid in gs[c.group].margins)
    return _assess(gs, ids, apps, rows, app)


def assess_group(g, rows=None, only: tuple | None = None) -> Assessment:
    """The assessment of one group's rows (or rows ``rows``) over its own margins, in their order (a compiled
    kernel's group may hold only some, in its own order), or over those of constraints ``only`` it holds."""
    ids = tuple(g.margins) if only is None else tuple(c for c in only if c in g.margins)
    return _assess({g.name: g}, ids, None, rows, None)


def _assess(gs: dict, ids: tuple, apps, rows, app) -> Assessment:
    cols = columns_of(ids)
    cons = cols.constraints
    if rows is None:  # the group's own arrays (the optimisers' inner loops: no copy)
        m = [gs[c.group].margins[c.id] for c in cons]
        def st():
            return [gs[c.group].state.get(c.id) for c in cons]
    else:
        m = [np.asarray(gs[c.group].margins[c.id])[rows] for c in cons]
        st = [np.asarray(gs[c.group].state[c.id])[rows] if c.id in gs[c.group].state else None for c in cons]
    unless = {}
    for j, key in cols.unless:
        v = gs[cons[j].group].values
        if key in v:
            unless[j] = _take(v[key], rows)
    n = len(m[0]) if m else len(_take(np.arange(max((len(g) for g in gs.values()), default=0)), rows))
    out = Assessment(cols, m, st, unless, n=n)
    if apps is not None:
        out.assumed = _assumed(out, gs, apps, rows, app)
    return out


def _assumed(a: Assessment, gs: dict, apps, rows, app) -> np.ndarray:
    """``(n, k)`` the evaluated checks that used a documented default of their application's inputs."""
    out = np.zeros((len(a), len(a.columns.ids)), dtype=bool)
    seen: dict = {}
    for j, c in enumerate(a.columns.constraints):
        xs = [x for x in c.assumes if x in DEFAULTS]
        if not xs:
            continue
        if c.group not in seen:
            g = gs[c.group]
            if app is not None:
                seen[c.group] = np.asarray(app)
            elif "app" in g.values:
                seen[c.group] = _take(g.values["app"], rows).astype(np.int64)
            else:
                seen[c.group] = _take(np.arange(len(g)), rows)
        aa = seen[c.group]
        for x in xs:
            out[:, j] |= apps.assumed(x)[aa]
    return out & a.evaluated
