"""The catalog selection of one tensioner: a linear MILP and a bilinear MINLP (Pyomo), and the MILP in cvxpy.

Every builder is a function of plain data, :class:`SelectionData` (the
feasible (core, option) pairs of each subsystem, their margins, and the
additive score coefficients of the current stage), returning a model (rules
named ``*_rule``) with mutable parameters for the lexicographic stages
(``t_lb``: a floor on the margin, ``add_ub``: a ceiling on the additive score).
The data come from synth's evaluator (:mod:`synth.optimise.model_data`); nothing
here imports synth.

* :func:`milp_model` (linearised, solved by HiGHS): one binary ``x[c]`` per
  core and one binary ``w[s, c, k]`` per feasible (core, option) pair,
  ``sum_c x = 1``, ``sum_k w[s, c, k] = x[c]``. The margin ``t`` is bounded by
  ``sum m[s,c,k] w[s,c,k]`` (exactly one pair per subsystem is selected, so
  no big-M is needed).
* :func:`minlp_model` (solved globally by SCIP): binaries per family only,
  ``x[c]`` and ``z[s, k]``, one each; feasibility and margin are the bilinear
  sums ``sum_{c,k} g[s,c,k] x[c] z[s,k]`` (``g = 1`` on feasible pairs and the
  product term picks the selected pair's coefficient).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pyomo.environ as pyo

__all__ = ["SelectionData", "milp_model", "minlp_model", "milp_problem"]


@dataclass
class SelectionData:
    """Coefficients of the selection models (plain numpy).

    ``subsystems``: names; ``n_options[s]``; ``feas[s]``: bool ``(n_cores, n_options[s])``;
    ``margin[s]``: objective margins ``(n_cores, n_options[s])``; ``core_margin``: ``(n_cores,)``;
    ``core_score`` / ``option_score[s]``: dicts name -> coefficient vector, combined by
    :meth:`add` with a stage's weights.
    """

    subsystems: tuple
    feas: dict
    margin: dict
    core_margin: np.ndarray
    core_score: dict
    option_score: dict

    @property
    def n_cores(self) -> int:
        return len(self.core_margin)

    def n_options(self, s) -> int:
        return self.feas[s].shape[1]

    def pairs(self, s):
        """``(i, j)`` index arrays of the feasible (core, option) pairs of subsystem ``s``."""
        return np.nonzero(self.feas[s])

    def add(self, weights: dict, s=None) -> np.ndarray:
        """The additive coefficients ``sum_k w_k score_k`` of the cores (``s`` None) or of subsystem ``s``."""
        src = self.core_score if s is None else self.option_score[s]
        out = np.zeros(len(next(iter(src.values()))))
        for k, w in weights.items():
            if k in src:
                out = out + w * src[k]
        return out


def _common(m, md, weights, margin_weight):
    m.t_lb = pyo.Param(mutable=True, initialize=-1e6)
    m.add_ub = pyo.Param(mutable=True, initialize=1e12)
    lo = float(min([md.core_margin.min()] + [md.margin[s].min() for s in md.subsystems if md.margin[s].size] + [0.0]))
    m.t = pyo.Var(bounds=(lo - 1.0, float(max([md.core_margin.max()] + [0.0]) + 1.0)))
    m.margin_weight = margin_weight


def _bounds_and_objective(m, weights, margin_weight, with_margin):
    """Margin floor, additive ceiling (lexicographic stages) and the objective, shared by both models."""
    m.floor = pyo.Constraint(rule=lambda m: m.t >= m.t_lb)
    m.ceiling = pyo.Constraint(rule=lambda m: m.additive <= m.add_ub)

    def objective_rule(m):
        if with_margin and not weights:
            return -m.t
        return m.additive - margin_weight * m.t
    m.obj = pyo.Objective(rule=objective_rule, sense=pyo.minimize)
    return m


def milp_model(md, weights: dict, margin_weight: float = 0.0, with_margin: bool = False) -> pyo.ConcreteModel:
    """Linearised selection MILP (combination binaries on feasible pairs)."""
    m = pyo.ConcreteModel("tensioner_milp")
    m.C = pyo.RangeSet(0, md.n_cores - 1)
    pairs = [(s, int(c), int(k)) for s in md.subsystems for c, k in zip(*md.pairs(s))]
    m.P = pyo.Set(initialize=pairs, dimen=3)
    m.x = pyo.Var(m.C, domain=pyo.Binary)
    m.w = pyo.Var(m.P, domain=pyo.Binary)
    _common(m, md, weights, margin_weight)
    by_sc = {}
    for s, c, k in pairs:
        by_sc.setdefault((s, c), []).append(k)
    a_core = md.add(weights)
    a_opt = {s: md.add(weights, s) for s in md.subsystems}

    def one_core_rule(m):
        return sum(m.x[c] for c in m.C) == 1
    m.one_core = pyo.Constraint(rule=one_core_rule)

    def link_rule(m, s, c):
        return sum(m.w[s, c, k] for k in by_sc.get((s, c), [])) == m.x[c]
    m.link = pyo.Constraint(list(md.subsystems), m.C, rule=link_rule)

    def additive(m):
        return sum(float(a_core[c]) * m.x[c] for c in m.C) + sum(float(a_opt[s][k]) * m.w[s, c, k] for s, c, k in m.P)
    m.additive = pyo.Expression(rule=additive)

    def core_margin_rule(m):
        return m.t <= sum(float(md.core_margin[c]) * m.x[c] for c in m.C)
    m.core_margin = pyo.Constraint(rule=core_margin_rule)

    def sub_margin_rule(m, s):
        return m.t <= sum(float(md.margin[s][c, k]) * m.w[s, c, k] for (s2, c, k) in m.P if s2 == s)
    m.sub_margin = pyo.Constraint(list(md.subsystems), rule=sub_margin_rule)

    return _bounds_and_objective(m, weights, margin_weight, with_margin)


def minlp_model(md, weights: dict, margin_weight: float = 0.0, with_margin: bool = False) -> pyo.ConcreteModel:
    """Family-binary MINLP with bilinear feasibility and margin constraints."""
    m = pyo.ConcreteModel("tensioner_minlp")
    m.C = pyo.RangeSet(0, md.n_cores - 1)
    m.Z = pyo.Set(initialize=[(s, int(k)) for s in md.subsystems for k in range(md.n_options(s))], dimen=2)
    m.x = pyo.Var(m.C, domain=pyo.Binary)
    m.z = pyo.Var(m.Z, domain=pyo.Binary)
    _common(m, md, weights, margin_weight)
    a_core = md.add(weights)
    a_opt = {s: md.add(weights, s) for s in md.subsystems}

    m.one_core = pyo.Constraint(rule=lambda m: sum(m.x[c] for c in m.C) == 1)

    def one_option_rule(m, s):
        return sum(m.z[s, k] for k in range(md.n_options(s))) == 1
    m.one_option = pyo.Constraint(list(md.subsystems), rule=one_option_rule)

    def feasible_pair_rule(m, s):
        c_idx, k_idx = md.pairs(s)
        return sum(m.x[int(c)] * m.z[s, int(k)] for c, k in zip(c_idx, k_idx)) == 1
    m.feasible_pair = pyo.Constraint(list(md.subsystems), rule=feasible_pair_rule)

    def additive(m):
        return sum(float(a_core[c]) * m.x[c] for c in m.C) + sum(float(a_opt[s][k]) * m.z[s, k] for s, k in m.Z)
    m.additive = pyo.Expression(rule=additive)

    m.core_margin = pyo.Constraint(rule=lambda m: m.t <= sum(float(md.core_margin[c]) * m.x[c] for c in m.C))

    def sub_margin_rule(m, s):
        c_idx, k_idx = md.pairs(s)
        return m.t <= sum(float(md.margin[s][c, k]) * m.x[int(c)] * m.z[s, int(k)] for c, k in zip(c_idx, k_idx))
    m.sub_margin = pyo.Constraint(list(md.subsystems), rule=sub_margin_rule)

    return _bounds_and_objective(m, weights, margin_weight, with_margin)


def milp_problem(md: SelectionData, weights: dict, margin_weight: float, with_margin: bool, t_lb: float,
                 add_ub: float):
    """The linearised MILP in cvxpy for one stage: ``(problem, x, w_by_subsystem, t, additive, pairs)``.

    Variables: ``x`` (one binary per core) and ``w`` (one binary per feasible
    (core, option) pair, per subsystem); ``t`` the margin. Constraints:
    ``sum x = 1``; ``L_s w = x`` (``L_s`` maps pairs to their core);
    ``t <= m_core @ x``; ``t <= m_s @ w_s``; the stage floor on ``t`` and
    ceiling on the additive score.
    """
    import cvxpy as cp
    import scipy.sparse as sps
    n = md.n_cores
    x = cp.Variable(n, boolean=True)
    t = cp.Variable()
    cons = [cp.sum(x) == 1, t >= t_lb]
    additive = md.add(weights) @ x
    ws, pairs = {}, {}
    for s in md.subsystems:
        ci, ki = md.pairs(s)
        pairs[s] = (ci, ki)
        w = cp.Variable(len(ci), boolean=True)
        ws[s] = w
        link = sps.csr_matrix((np.ones(len(ci)), (ci, np.arange(len(ci)))), shape=(n, len(ci)))
        cons.append(link @ w == x)
        cons.append(t <= md.margin[s][ci, ki] @ w)
        additive = additive + md.add(weights, s)[ki] @ w
    cons.append(t <= md.core_margin @ x)
    cons.append(additive <= add_ub)
    obj = -t if (with_margin and not weights) else additive - margin_weight * t
    return cp.Problem(cp.Minimize(obj), cons), x, ws, t, additive, pairs
