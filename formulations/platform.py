"""Platform rationalisation: the fewest standard parts that serve a whole portfolio.

A Pyomo set-cover / facility-location MILP as a function of plain numpy data
(:class:`PlatformInstance`); it imports nothing of ``synth``. The data come from
``synth.platform.compile`` (flattened feasibility of every application, pruned
provably, see ``synth.platform.prune``).

Data. Parts ``j`` (``part_family[j]``, weight ``w_j``, per-variant fixed cost ``F_j``).
A **pattern** ``k`` is a set of parts (``pattern_parts``): the parts of one core or of
one subsystem option. For each application ``a``: cores ``c`` (pattern ``k_c``, unit
cost ``u_c``) and **rows** ``r``: one per (subsystem ``s``, group ``g``) of the
application, holding the cores ``C_r`` of the group and the options ``O_r`` feasible
with them (pattern ``k_o``, unit cost ``u_o``). Costs arrive multiplied by the volume.

Variables. ``y_j`` binary: part ``j`` is in the platform. ``v_k in [0, 1]``: every part of
pattern ``k`` is in the platform (only for patterns of two or more parts; a one-part
pattern is its ``y_j``, an empty pattern is the constant 1; write ``V_k`` for either).
``x_c in [0, 1]``: the application of core ``c`` uses it. ``e_a in [0, 1]``: application
``a`` is not served (only with ``allow_unserved``). Cost objective: ``z_ro >= 0``, the
application of row ``r`` uses option ``o``.

Constraints (rules named ``*_rule``)::

    assign_rule       sum_{c of a} x_c + e_a = 1                       each application
    pattern_rule      v_k <= y_j                 for j in k, |k| >= 2
    core_link_rule    sum_{c of a, k_c = k} x_c <= V_k                 each (a, k)
    cover_rule        sum_{c in C_r} x_c <= sum_{o in O_r} V_{k_o}     variants objective
    flow_rule         sum_{c in C_r} x_c  = sum_{o in O_r} z_ro        cost objective
    option_link_rule  sum_{r of (a, s)} sum_{o: k_o = k} z_ro <= V_k    cost objective, each (a, s, k)
    max_variants_rule sum_{j in f} y_j <= N_f                          optional, per family
    budget_rule       sum_j w_j y_j <= B                               optional (epsilon constraint)

Objective: ``variants``: ``sum_j w_j y_j + P sum_a e_a``; ``cost``:
``sum_j F_j y_j + sum_c u_c x_c + sum_ro u_o z_ro + P sum_a e_a``. ``P`` exceeds anything
a part saving can buy, so serving applications comes first.

Why ``x``, ``v``, ``z`` and ``e`` may be continuous. Fix an integral ``y`` (a platform).
The rest splits per application. The cover form (variants) is exact for a single core
and any feasible fractional ``x`` puts weight only on cores whose pattern and whose
groups are covered by the platform, so one such core serves the application integrally.
In the cost form, for fixed ``x`` the optimal ``z`` routes each row's weight to the
cheapest platform option of the row (``option_link`` caps the sum over the rows of one
subsystem, which is at most ``sum_c x_c <= 1``), so the cost is
``sum_c x_c (u_c + sum_s best_s(c))``: linear in ``x`` over a simplex, minimised at a
vertex, a single core. Hence a branch and bound on ``y`` alone is exact, and the
integral assignment is recovered per application afterwards.

Size. With ``n_rows`` rows and ``nnz_opt = sum_r |O_r|``: variables ``J + |v| + n_cores
(+ n_apps) (+ nnz_opt)``; non-zeros about ``n_cores * (2 + rows per core) + nnz_opt``
(variants) or ``3 nnz_opt`` (cost). The spring options dominate ``nnz_opt``; the
provable reductions of ``synth.platform.prune`` are what keep 1,000 applications small.

>>> import numpy as np
>>> inst = PlatformInstance(                                  # 2 apps, parts: A B C (one family)
...     family_names=["f"], part_family=np.array([0, 0, 0]), part_weight=np.ones(3),
...     part_fixed_cost=np.zeros(3), pattern_ptr=np.array([0, 1, 2, 3]), pattern_parts=np.array([0, 1, 2]),
...     n_apps=2, core_app=np.array([0, 1]), core_pattern=np.array([0, 2]), core_cost=np.zeros(2),
...     row_app=np.array([0, 1]), row_sub=np.array([0, 0]), row_core_ptr=np.array([0, 1, 2]),
...     row_core=np.array([0, 1]), row_opt_ptr=np.array([0, 2, 4]), row_opt_pattern=np.array([1, 2, 0, 2]),
...     row_opt_cost=np.zeros(4))
>>> r = solve(inst, "variants")
>>> r.status, r.objective, sorted(np.flatnonzero(r.y).tolist())
('optimal', 2.0, [0, 2])
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import pyomo.environ as pyo
from pyomo.core.expr.numeric_expr import LinearExpression

__all__ = ["PlatformInstance", "PlatformSolution", "build_model", "solve", "SOLVERS"]

#: solver name -> Pyomo solver (HiGHS through appsi, SCIP through PySCIPOpt)
SOLVERS = {"highs": "appsi_highs", "scip": "scip_direct"}


@dataclass
class PlatformInstance:
    """Plain-data instance (numpy arrays; CSR pairs ``*_ptr`` / values). See the module docstring."""

    family_names: list
    part_family: np.ndarray      # (J,) family index of each part
    part_weight: np.ndarray      # (J,) weight in the variants objective
    part_fixed_cost: np.ndarray  # (J,) per-variant fixed cost (cost objective)
    pattern_ptr: np.ndarray      # (K+1,) CSR: parts of each pattern
    pattern_parts: np.ndarray
    n_apps: int
    core_app: np.ndarray         # (C,) application of each core
    core_pattern: np.ndarray     # (C,)
    core_cost: np.ndarray        # (C,) unit cost x volume
    row_app: np.ndarray          # (R,)
    row_sub: np.ndarray          # (R,) subsystem index (rows of one (app, subsystem) partition its cores)
    row_core_ptr: np.ndarray     # (R+1,) CSR: cores of each row
    row_core: np.ndarray
    row_opt_ptr: np.ndarray      # (R+1,) CSR: options of each row
    row_opt_pattern: np.ndarray
    row_opt_cost: np.ndarray     # unit cost x volume

    @property
    def n_parts(self) -> int:
        return int(len(self.part_family))

    @property
    def n_patterns(self) -> int:
        return int(len(self.pattern_ptr) - 1)

    def pattern_len(self) -> np.ndarray:
        return np.diff(self.pattern_ptr)


@dataclass
class PlatformSolution:
    """What a solve returns: the platform ``y`` (bool per part) and how the solve went."""

    status: str                  # optimal | time_limit | infeasible | error
    y: np.ndarray | None
    objective: float
    bound: float
    gap: float
    time_s: float
    build_s: float
    size: dict = field(default_factory=dict)
    solver: str = "highs"
    unserved: np.ndarray | None = None   # bool per application (allow_unserved only)


def _groups(keys: np.ndarray):
    """``(first member, members)`` per distinct key (members as index arrays into ``keys``)."""
    order = np.argsort(keys, kind="stable")
    uk, start = np.unique(keys[order], return_index=True)
    bounds = np.append(start, len(order))
    return [order[bounds[i]:bounds[i + 1]] for i in range(len(uk))]


def _expand(ptr: np.ndarray, parts: np.ndarray, pattern: np.ndarray):
    """``(item, part)`` pairs: every part of the pattern of every item."""
    n = np.diff(ptr)[pattern]
    item = np.repeat(np.arange(len(pattern)), n)
    start = np.repeat(ptr[pattern], n)
    off = np.arange(len(item)) - np.repeat(np.cumsum(n) - n, n)
    return item, parts[start + off]


def _lin(coefs, vars_):
    return LinearExpression(constant=0.0, linear_coefs=list(coefs), linear_vars=list(vars_))


def build_model(inst: PlatformInstance, objective: str = "variants", *, max_variants: dict | None = None,
                budget: float | None = None, allow_unserved: bool = False) -> pyo.ConcreteModel:
    """The Pyomo model of ``inst`` (see the module docstring); ``max_variants``: ``{family name: N}``.

    ``m.budget`` is a mutable parameter (the epsilon constraint on the weighted part
    count, present when ``budget`` is not None) so a sweep can re-solve one model.
    ``m.size`` holds the counts of variables, binaries, constraints and non-zeros.
    """
    if objective not in ("variants", "cost"):
        raise ValueError(f"objective must be 'variants' or 'cost', got {objective!r}")
    m = pyo.ConcreteModel("platform")
    J, C, R = inst.n_parts, len(inst.core_app), len(inst.row_app)
    n_z = int(inst.row_opt_ptr[-1])
    # (core, part) and (option entry, part) incidences
    c_item, c_part = _expand(inst.pattern_ptr, inst.pattern_parts, inst.core_pattern)
    z_item, z_part = _expand(inst.pattern_ptr, inst.pattern_parts, inst.row_opt_pattern)
    in_use = np.zeros(J, bool)                     # a part in no core or option of any application: no variable
    in_use[c_part] = True
    in_use[z_part] = True
    m.J = pyo.Set(initialize=[int(j) for j in np.flatnonzero(in_use)])
    m.y = pyo.Var(m.J, domain=pyo.Binary)
    m.x = pyo.Var(range(C), bounds=(0, 1))
    m.z = pyo.Var(range(n_z), bounds=(0, 1))
    if allow_unserved:
        m.e = pyo.Var(range(inst.n_apps), bounds=(0, 1))
    nnz = 0

    app_ptr = np.searchsorted(inst.core_app, np.arange(inst.n_apps + 1))

    def assign_rule(m, a):
        xs = [m.x[c] for c in range(app_ptr[a], app_ptr[a + 1])] + ([m.e[a]] if allow_unserved else [])
        if not xs:
            return pyo.Constraint.Infeasible
        return _lin([1.0] * len(xs), xs) == 1
    m.assign = pyo.Constraint(range(inst.n_apps), rule=assign_rule)
    nnz += C + (inst.n_apps if allow_unserved else 0)

    def flow_rule(m, r):
        xs = [m.x[int(c)] for c in inst.row_core[inst.row_core_ptr[r]:inst.row_core_ptr[r + 1]]]
        zs = [m.z[i] for i in range(inst.row_opt_ptr[r], inst.row_opt_ptr[r + 1])]
        return _lin([1.0] * len(xs) + [-1.0] * len(zs), xs + zs) == 0
    m.flow = pyo.Constraint(range(R), rule=flow_rule)
    nnz += int(inst.row_core_ptr[-1]) + n_z

    cl = _groups(inst.core_app[c_item].astype(np.int64) * J + c_part)

    def core_link_rule(m, g):
        idx = cl[g]
        return _lin([1.0] * len(idx) + [-1.0], [m.x[int(c)] for c in c_item[idx]] + [m.y[int(c_part[idx[0]])]]) <= 0
    m.core_link = pyo.Constraint(range(len(cl)), rule=core_link_rule)
    nnz += len(c_item) + len(cl)

    z_row = np.repeat(np.arange(R), np.diff(inst.row_opt_ptr))[z_item]
    ol = _groups((inst.row_app[z_row].astype(np.int64) * 64 + inst.row_sub[z_row]) * J + z_part)

    def option_link_rule(m, g):
        idx = ol[g]
        return _lin([1.0] * len(idx) + [-1.0], [m.z[int(i)] for i in z_item[idx]] + [m.y[int(z_part[idx[0]])]]) <= 0
    m.option_link = pyo.Constraint(range(len(ol)), rule=option_link_rule)
    nnz += len(z_item) + len(ol)

    fam_idx = {n: i for i, n in enumerate(inst.family_names)}
    caps = [(f, int(n)) for f, n in (max_variants or {}).items()]
    for f, _ in caps:
        if f not in fam_idx:
            raise ValueError(f"max_variants: unknown family {f!r}; families: {list(inst.family_names)}")

    def max_variants_rule(m, f, n):
        js = np.flatnonzero((inst.part_family == fam_idx[f]) & in_use)
        if len(js) <= n:
            return pyo.Constraint.Skip
        return _lin([1.0] * len(js), [m.y[int(j)] for j in js]) <= n
    m.max_variants = pyo.Constraint(caps, rule=max_variants_rule)
    nnz += sum(int(np.sum((inst.part_family == fam_idx[f]) & in_use)) for f, _ in caps)
    m.budget = pyo.Param(mutable=True, initialize=0.0 if budget is None else float(budget))
    if budget is not None:
        m.budget_con = pyo.Constraint(expr=_lin([float(inst.part_weight[j]) for j in m.J], [m.y[j] for j in m.J]) <= m.budget)
        nnz += int(in_use.sum())

    if objective == "variants":
        terms = [(float(inst.part_weight[j]), m.y[j]) for j in m.J if inst.part_weight[j] != 0]
        pen = float(np.sum(inst.part_weight[in_use])) + 1.0
    else:
        terms = [(float(inst.part_fixed_cost[j]), m.y[j]) for j in m.J if inst.part_fixed_cost[j] != 0]
        terms += [(float(inst.core_cost[c]), m.x[c]) for c in range(C) if inst.core_cost[c] != 0]
        terms += [(float(inst.row_opt_cost[i]), m.z[i]) for i in range(n_z) if inst.row_opt_cost[i] != 0]
        pen = float(np.sum(inst.part_fixed_cost[in_use]) + np.sum(np.abs(inst.core_cost))
                    + np.sum(np.abs(inst.row_opt_cost))) + 1.0
    if allow_unserved:
        m.penalty = pen
        terms += [(pen, m.e[a]) for a in range(inst.n_apps)]
    m.obj = pyo.Objective(expr=_lin([t[0] for t in terms], [t[1] for t in terms]), sense=pyo.minimize)
    n_var = int(in_use.sum()) + C + n_z + (inst.n_apps if allow_unserved else 0)
    n_con = sum(len(c) for c in m.component_objects(pyo.Constraint, active=True))
    m.size = {"variables": n_var, "binaries": int(in_use.sum()), "constraints": int(n_con), "nonzeros": int(nnz)}
    return m


def _result_values(res):
    bound = getattr(res, "best_objective_bound", None)
    feas = getattr(res, "best_feasible_objective", None)
    return (np.nan if feas is None else float(feas)), (np.nan if bound is None else float(bound))


def solve(inst: PlatformInstance, objective: str = "variants", *, solver: str = "highs", time_limit: float = 60.0,
          mip_gap: float = 0.0, max_variants: dict | None = None, budget: float | None = None,
          allow_unserved: bool = False, warm_start: np.ndarray | None = None, model=None) -> PlatformSolution:
    """Build (unless ``model`` is given) and solve; ``warm_start``: a bool platform (e.g. the greedy one).

    ``status`` is ``optimal`` (gap within ``mip_gap``), ``time_limit`` (best platform found,
    gap reported), ``infeasible`` or ``error``.
    """
    if solver not in SOLVERS:
        raise ValueError(f"solver must be one of {sorted(SOLVERS)}, got {solver!r}")
    t0 = time.perf_counter()
    if inst.n_apps == 0:                       # nothing to serve: the empty platform
        return PlatformSolution("optimal", np.zeros(inst.n_parts, bool), 0.0, 0.0, 0.0, 0.0, 0.0,
                                {"variables": 0, "binaries": 0, "constraints": 0, "nonzeros": 0}, solver)
    m = model if model is not None else build_model(inst, objective, max_variants=max_variants, budget=budget,
                                                    allow_unserved=allow_unserved)
    build_s = time.perf_counter() - t0
    J = inst.n_parts
    if warm_start is not None:
        for j in m.y:
            m.y[j].set_value(float(bool(warm_start[j])))
    t1 = time.perf_counter()
    if solver == "highs":
        from pyomo.contrib.appsi.solvers import Highs
        from pyomo.contrib.appsi.base import TerminationCondition as TC
        opt = Highs()
        opt.config.time_limit = float(time_limit)
        opt.config.mip_gap = float(mip_gap)
        opt.config.load_solution = False
        opt.config.warmstart = warm_start is not None
        res = opt.solve(m)
        tc = res.termination_condition
        obj, bound = _result_values(res)
        has = res.best_feasible_objective is not None
        if has:
            res.solution_loader.load_vars()
        status = {TC.optimal: "optimal", TC.maxTimeLimit: "time_limit", TC.infeasible: "infeasible",
                  TC.infeasibleOrUnbounded: "infeasible"}.get(tc, "error")
    else:
        opt = pyo.SolverFactory(SOLVERS[solver])
        opts = {"limits/time": float(time_limit), "limits/gap": float(mip_gap)}
        res = opt.solve(m, options=opts, load_solutions=False, warmstart=warm_start is not None)
        tc = str(res.solver.termination_condition).split(".")[-1]
        has = len(res.solution) > 0
        if has:
            m.solutions.load_from(res)
        status = {"optimal": "optimal", "maxTimeLimit": "time_limit", "infeasible": "infeasible"}.get(tc, "error")
        obj = float(pyo.value(m.obj)) if has else np.nan
        lb = res.problem.lower_bound
        bound = float(lb) if lb is not None and np.isfinite(float(lb)) else np.nan
    solve_s = time.perf_counter() - t1
    y = None
    if has:
        y = np.zeros(J, bool)
        for j in m.y:
            y[j] = (pyo.value(m.y[j]) or 0.0) > 0.5
    unserved = None
    if has and allow_unserved:
        unserved = np.array([(pyo.value(m.e[a]) or 0.0) > 0.5 for a in range(inst.n_apps)], bool)
    if has and np.isfinite(obj) and np.isfinite(bound):
        gap = abs(obj - bound) / max(abs(obj), 1e-9)
    else:
        gap = 0.0 if status == "optimal" else np.nan
    return PlatformSolution(status=status, y=y, objective=obj, bound=bound, gap=gap, time_s=solve_s, build_s=build_s,
                            size=dict(m.size), solver=solver, unserved=unserved)
