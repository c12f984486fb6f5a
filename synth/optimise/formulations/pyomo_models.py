"""Pyomo models of the catalog selection: a linear MILP and a nonlinear (bilinear) MINLP.

Both are functions of :class:`~synth.optimise.formulations.data.ModelData`
returning a ``ConcreteModel`` (rules named ``*_rule``), with mutable
parameters for the lexicographic stages (``t_lb``: a floor on the margin,
``add_ub``: a ceiling on the additive score).

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

import pyomo.environ as pyo

from synth.optimise.space import SUBSYSTEMS

__all__ = ["milp_model", "minlp_model"]


def _common(m, md, weights, margin_weight):
    m.t_lb = pyo.Param(mutable=True, initialize=-1e6)
    m.add_ub = pyo.Param(mutable=True, initialize=1e12)
    lo = float(min([md.core_margin.min()] + [md.margin[s].min() for s in SUBSYSTEMS if md.margin[s].size] + [0.0]))
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
    pairs = [(s, int(c), int(k)) for s in SUBSYSTEMS for c, k in zip(*md.pairs(s))]
    m.P = pyo.Set(initialize=pairs, dimen=3)
    m.x = pyo.Var(m.C, domain=pyo.Binary)
    m.w = pyo.Var(m.P, domain=pyo.Binary)
    _common(m, md, weights, margin_weight)
    by_sc = {}
    for s, c, k in pairs:
        by_sc.setdefault((s, c), []).append(k)
    a_core = md.add(weights, "core")
    a_opt = {s: md.add(weights, "opt", s) for s in SUBSYSTEMS}

    def one_core_rule(m):
        return sum(m.x[c] for c in m.C) == 1
    m.one_core = pyo.Constraint(rule=one_core_rule)

    def link_rule(m, s, c):
        return sum(m.w[s, c, k] for k in by_sc.get((s, c), [])) == m.x[c]
    m.link = pyo.Constraint(list(SUBSYSTEMS), m.C, rule=link_rule)

    def additive(m):
        return sum(float(a_core[c]) * m.x[c] for c in m.C) + sum(float(a_opt[s][k]) * m.w[s, c, k] for s, c, k in m.P)
    m.additive = pyo.Expression(rule=additive)

    def core_margin_rule(m):
        return m.t <= sum(float(md.core_margin[c]) * m.x[c] for c in m.C)
    m.core_margin = pyo.Constraint(rule=core_margin_rule)

    def sub_margin_rule(m, s):
        return m.t <= sum(float(md.margin[s][c, k]) * m.w[s, c, k] for (s2, c, k) in m.P if s2 == s)
    m.sub_margin = pyo.Constraint(list(SUBSYSTEMS), rule=sub_margin_rule)

    return _bounds_and_objective(m, weights, margin_weight, with_margin)


def minlp_model(md, weights: dict, margin_weight: float = 0.0, with_margin: bool = False) -> pyo.ConcreteModel:
    """Family-binary MINLP with bilinear feasibility and margin constraints."""
    m = pyo.ConcreteModel("tensioner_minlp")
    m.C = pyo.RangeSet(0, md.n_cores - 1)
    m.Z = pyo.Set(initialize=[(s, int(k)) for s in SUBSYSTEMS for k in range(len(md.opts[s]))], dimen=2)
    m.x = pyo.Var(m.C, domain=pyo.Binary)
    m.z = pyo.Var(m.Z, domain=pyo.Binary)
    _common(m, md, weights, margin_weight)
    a_core = md.add(weights, "core")
    a_opt = {s: md.add(weights, "opt", s) for s in SUBSYSTEMS}

    m.one_core = pyo.Constraint(rule=lambda m: sum(m.x[c] for c in m.C) == 1)

    def one_option_rule(m, s):
        return sum(m.z[s, k] for k in range(len(md.opts[s]))) == 1
    m.one_option = pyo.Constraint(list(SUBSYSTEMS), rule=one_option_rule)

    def feasible_pair_rule(m, s):
        c_idx, k_idx = md.pairs(s)
        return sum(m.x[int(c)] * m.z[s, int(k)] for c, k in zip(c_idx, k_idx)) == 1
    m.feasible_pair = pyo.Constraint(list(SUBSYSTEMS), rule=feasible_pair_rule)

    def additive(m):
        return sum(float(a_core[c]) * m.x[c] for c in m.C) + sum(float(a_opt[s][k]) * m.z[s, k] for s, k in m.Z)
    m.additive = pyo.Expression(rule=additive)

    m.core_margin = pyo.Constraint(rule=lambda m: m.t <= sum(float(md.core_margin[c]) * m.x[c] for c in m.C))

    def sub_margin_rule(m, s):
        c_idx, k_idx = md.pairs(s)
        return m.t <= sum(float(md.margin[s][c, k]) * m.x[int(c)] * m.z[s, int(k)] for c, k in zip(c_idx, k_idx))
    m.sub_margin = pyo.Constraint(list(SUBSYSTEMS), rule=sub_margin_rule)

    return _bounds_and_objective(m, weights, margin_weight, with_margin)
