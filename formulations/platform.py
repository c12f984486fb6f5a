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
    pool_rule         s_e <= V_j                                        cost objective, each volume break e of j
    break_on_rule     s_e <= Vmax_j b_e
    break_reach_rule  q_e b_e <= V_j
    max_variants_rule sum_{j in f} y_j <= N_f                          optional, per family
    budget_rule       sum_j w_j y_j <= B                               optional (epsilon constraint)

**Volume breaks** (cost objective, optional: ``break_ptr``, ``break_qty``, ``break_step``, ``app_volume``). Part
``j``'s unit price falls by ``d_e`` once its volume ``V_j = sum_c vol_a(c) x_c [j in k_c] + sum_i vol_a(i) z_i
[j in k_i]`` (pieces a year of every application whose design holds it) reaches the break's quantity ``q_e``
(an all-units quantity discount: every piece gets the lower price). ``b_e`` binary: the break is reached;
``s_e in [0, Vmax_j]`` the volume it discounts (``Vmax_j``: the summed volume of every application that can use
``j``); the objective gets ``- sum_e d_e s_e``. With ``d_e >= 0`` the minimum puts ``s_e = V_j`` when ``b_e = 1``
(allowed only when ``V_j >= q_e``) and 0 otherwise, so the cost of part ``j`` is exactly ``p_j(V_j) V_j``, the
unit costs ``u`` holding each part at its price below the first break (:func:`synth.platform.volume.pool_prices`).
A fractional assignment could reach a break with a share of an application, so there the ``x`` of every core of an
application with a break part in some design and the ``z`` of every option holding one are binary; the other
``z`` stay continuous (with those fixed, the rest of a row is a simplex with fixed costs: a vertex, one option).

Objective: ``variants``: ``sum_j w_j y_j + P sum_a e_a``; ``cost``:
``sum_j F_j y_j + sum_c u_c x_c + sum_ro u_o z_ro - sum_e d_e s_e + P sum_a e_a``. ``P`` exceeds anything
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
integral assignment is recovered per application afterwards (with volume breaks: see above; the
solution's ``x`` and ``z`` are then the designs).

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

import os
import sys
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:   # Pyomo is imported where the reference model is built (the arrays path never needs it)
    import pyomo.environ as pyo

__all__ = ["PlatformInstance", "PlatformSolution", "MilpArrays", "build_model", "build_arrays", "highs_model", "solve",
           "designs_start", "SOLVERS", "BUILDS", "NODE_LIMIT", "TIME_LIMIT_S", "HIGHS_THREADS"]

#: solver name -> Pyomo solver (HiGHS through appsi, SCIP through PySCIPOpt)
SOLVERS = {"highs": "appsi_highs", "scip": "scip_direct"}
#: how the HiGHS model is built: ``arrays`` (:func:`build_arrays` handed to highspy, HiGHS's own Python API) or
#: ``pyomo`` (:func:`build_model` through Pyomo's appsi interface: the reference, and SCIP's only path)
BUILDS = ("arrays", "pyomo")
#: Branch-and-bound nodes a solve may take by default (HiGHS ``mip_max_nodes``, SCIP ``limits/nodes``): the limit
#: that makes a solve reproducible. A node count is the same on every machine and under any load, a number of seconds
#: is not; where it binds, the status is ``node_limit`` and the platform is the best one found in those nodes, the
#: same on every run. HiGHS has no deterministic work limit (Gurobi's ``WorkLimit``); its simplex iteration limit does
#: not reach the MIP's subproblems. Chosen so that it binds only on the hard instances: ``portfolio-sample`` 1,000
#: applications solve at the root (1 node), and so do 10,000 (``docs/model.md``, "Platform rationalisation").
NODE_LIMIT = 10_000
#: Wall-clock seconds a solve may take by default: a safety net only, well above what the benchmarked solves take on a
#: busy machine (10,000 applications: 25 s CPU, 111 s of wall at load 12; the former 60 s bound there). Where it binds (status ``time_limit``) the platform depends on the machine and its load, and every output
#: says so: "stopped at the time limit: not reproducible".
TIME_LIMIT_S = 600.0
#: Threads HiGHS runs on: one. HiGHS 1.16's branch and bound takes another path with more threads (the hitting-set
#: portfolio of ``tests/test_platform_limits.py``, ``hitting_set_portfolio(150, 60, 3, 0)``: 165 nodes on 1 thread, 176 on 2, 234 on 4, and
#: on 2 threads another platform of the same size), and HiGHS's default (``threads`` 0) is half the machine's cores:
#: the platform would follow the machine even where the solve is optimal (ties) and more so where a limit binds.
HIGHS_THREADS = 1


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
    app_volume: np.ndarray | None = None   # (n_apps,) pieces a year (the volume breaks' only)
    break_ptr: np.ndarray | None = None    # (J+1,) CSR: the quantity breaks of each part (cost objective)
    break_qty: np.ndarray | None = None    # quantity q of each break [pieces a year]
    break_step: np.ndarray | None = None   # the part's unit price falls by this [EUR] once its volume reaches q

    @property
    def n_breaks(self) -> int:
        return 0 if self.break_ptr is None else int(self.break_ptr[-1])

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

    status: str                  # optimal | node_limit | time_limit | infeasible | error
    y: np.ndarray | None
    objective: float
    bound: float
    gap: float
    time_s: float
    build_s: float
    size: dict = field(default_factory=dict)
    solver: str = "highs"
    unserved: np.ndarray | None = None   # bool per application (allow_unserved only)
    x: np.ndarray | None = None          # bool per core and per option entry: the designs of the solution
    z: np.ndarray | None = None          # (with volume breaks only: the platform alone does not fix them)
    nodes: int = -1                      # branch-and-bound nodes the solve took (-1: not known)


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


@dataclass
class _Breaks:
    """The volume breaks of an instance, as both builds read them: per break ``e`` its part, quantity, step and the
    largest volume ``vmax`` its part can have; per part the cores (``core``, CSR ``core_ptr``) and option entries
    (``opt``, ``opt_ptr``) holding it, ascending, with the volume of their application (``core_vol``, ``opt_vol``)."""

    part: np.ndarray
    qty: np.ndarray
    step: np.ndarray
    vmax: np.ndarray
    x_int: np.ndarray            # (C,) bool: x_c integral (every core of an application one of whose designs
    z_int: np.ndarray            # has a part with a break); (n_z,) bool: z_i integral (its option has one)
    core_ptr: np.ndarray
    core: np.ndarray
    core_vol: np.ndarray
    opt_ptr: np.ndarray
    opt: np.ndarray
    opt_vol: np.ndarray

    def __len__(self) -> int:
        return int(len(self.part))

    def terms(self, e: int) -> tuple:
        """``(cores, their volumes, option entries, their volumes)`` of break ``e``'s part: its volume ``V_j``."""
        j = int(self.part[e])
        c0, c1, o0, o1 = self.core_ptr[j], self.core_ptr[j + 1], self.opt_ptr[j], self.opt_ptr[j + 1]
        return self.core[c0:c1], self.core_vol[c0:c1], self.opt[o0:o1], self.opt_vol[o0:o1]


def _breaks(inst: PlatformInstance, objective: str, c_item, c_part, z_item, z_part) -> _Breaks | None:
    """The :class:`_Breaks` of ``inst`` (cost objective with breaks only, else None)."""
    if objective != "cost" or not inst.n_breaks:
        return None
    J = inst.n_parts
    vol = np.asarray(inst.app_volume, float)
    z_row = np.repeat(np.arange(len(inst.row_app)), np.diff(inst.row_opt_ptr))
    c_app, z_app = inst.core_app[c_item], inst.row_app[z_row[z_item]]
    oc, oz = np.argsort(c_part, kind="stable"), np.argsort(z_part, kind="stable")
    pairs = np.unique(np.concatenate([c_app * J + c_part, z_app * J + z_part]).astype(np.int64))
    vmax = np.bincount(pairs % J, weights=vol[pairs // J], minlength=J)
    part = np.repeat(np.arange(J), np.diff(inst.break_ptr))
    has = np.diff(inst.break_ptr) > 0
    z_int = np.zeros(int(inst.row_opt_ptr[-1]), bool)
    z_int[z_item[has[z_part]]] = True
    app_int = np.zeros(inst.n_apps, bool)
    app_int[c_app[has[c_part]]] = True
    app_int[z_app[has[z_part]]] = True
    return _Breaks(part=part, qty=np.asarray(inst.break_qty, float), step=np.asarray(inst.break_step, float),
                   vmax=vmax[part], x_int=app_int[inst.core_app], z_int=z_int, core_ptr=np.searchsorted(c_part[oc], np.arange(J + 1)), core=c_item[oc],
                   core_vol=vol[c_app[oc]], opt_ptr=np.searchsorted(z_part[oz], np.arange(J + 1)), opt=z_item[oz],
                   opt_vol=vol[z_app[oz]])


def _lin(coefs, vars_):
    from pyomo.core.expr.numeric_expr import LinearExpression
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
    import pyomo.environ as pyo
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
    br = _breaks(inst, objective, c_item, c_part, z_item, z_part)
    if br:   # with volume breaks the x and z of designs holding a part with a break are integral
        m.x = pyo.Var(range(C), domain=lambda m, c: pyo.Binary if br.x_int[c] else pyo.Reals, bounds=(0, 1))
        m.z = pyo.Var(range(n_z), domain=lambda m, i: pyo.Binary if br.z_int[i] else pyo.Reals, bounds=(0, 1))
    else:
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
    nb = len(br) if br else 0
    if br:
        m.s = pyo.Var(range(nb), bounds=lambda m, e: (0.0, float(br.vmax[e])))
        m.b = pyo.Var(range(nb), domain=pyo.Binary)

        def volume_terms(m, e):
            cs, cv, zs, zv = br.terms(e)
            return [-float(v) for v in cv] + [-float(v) for v in zv], [m.x[int(c)] for c in cs] + [m.z[int(i)] for i in zs]

        def pool_rule(m, e):
            coefs, vars_ = volume_terms(m, e)
            return _lin([1.0] + coefs, [m.s[e]] + vars_) <= 0
        m.pool = pyo.Constraint(range(nb), rule=pool_rule)

        def break_on_rule(m, e):
            return _lin([1.0, -float(br.vmax[e])], [m.s[e], m.b[e]]) <= 0
        m.break_on = pyo.Constraint(range(nb), rule=break_on_rule)

        def break_reach_rule(m, e):
            coefs, vars_ = volume_terms(m, e)
            return _lin([float(br.qty[e])] + coefs, [m.b[e]] + vars_) <= 0
        m.break_reach = pyo.Constraint(range(nb), rule=break_reach_rule)
        n_use = int(sum(br.core_ptr[j + 1] - br.core_ptr[j] + br.opt_ptr[j + 1] - br.opt_ptr[j] for j in br.part))
        nnz += 2 * (nb + n_use) + 2 * nb

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
        terms += [(-float(br.step[e]), m.s[e]) for e in range(nb)]
        pen = float(np.sum(inst.part_fixed_cost[in_use]) + np.sum(np.abs(inst.core_cost))
                    + np.sum(np.abs(inst.row_opt_cost))) + 1.0
    if allow_unserved:
        m.penalty = pen
        terms += [(pen, m.e[a]) for a in range(inst.n_apps)]
    m.obj = pyo.Objective(expr=_lin([t[0] for t in terms], [t[1] for t in terms]), sense=pyo.minimize)
    n_var = int(in_use.sum()) + C + n_z + (inst.n_apps if allow_unserved else 0) + 2 * nb
    n_con = sum(len(c) for c in m.component_objects(pyo.Constraint, active=True))
    m.size = {"variables": n_var, "binaries": int(in_use.sum()) + (nb + int(br.x_int.sum() + br.z_int.sum()) if nb else 0),
              "constraints": int(n_con), "nonzeros": int(nnz)}
    return m


@dataclass
class MilpArrays:
    """The MILP of :func:`build_model` as plain arrays, in the form HiGHS receives it from Pyomo's appsi interface
    (so both builds hand HiGHS the same model, column for column): columns in the order of their first appearance
    in the constraints, rows in the order of the constraint components, each row's entries in the order of its
    expression; rows as CSR (``row_start`` holds ``n_rows + 1`` offsets)."""

    col_lower: np.ndarray
    col_upper: np.ndarray
    col_cost: np.ndarray
    col_integer: np.ndarray      # bool per column (the ``y_j``)
    row_lower: np.ndarray
    row_upper: np.ndarray
    row_start: np.ndarray
    row_index: np.ndarray        # column of each entry
    row_value: np.ndarray
    y_col: np.ndarray            # (J,) column of ``y_j``, -1 for a part without a variable
    x_col: np.ndarray            # (C,) column of ``x_c``
    z_col: np.ndarray            # (n_z,) column of ``z_i``
    sb_col: np.ndarray           # (2 n_breaks,) columns of ``s_e`` then ``b_e``
    e_col: np.ndarray | None     # (n_apps,) column of ``e_a`` (``allow_unserved`` only)
    size: dict


def _group_rows(keys: np.ndarray):
    """``(order, ptr)``: the members of each distinct key (as :func:`_groups`, in one CSR)."""
    order = np.argsort(keys, kind="stable")
    _, start = np.unique(keys[order], return_index=True)
    return order, np.append(start, len(order)).astype(np.int64)


def _rows(ptr1, idx1, val1, ptr2, idx2, val2):
    """Row-wise concatenation of two CSR blocks of as many rows: each row's entries of the first, then the second."""
    n1, n2 = np.diff(ptr1), np.diff(ptr2)
    start = np.concatenate([[0], np.cumsum(n1 + n2)]).astype(np.int64)
    idx, val = np.empty(start[-1], np.int64), np.empty(start[-1])
    r1, r2 = np.repeat(np.arange(len(n1)), n1), np.repeat(np.arange(len(n2)), n2)
    p1 = start[r1] + np.arange(len(r1)) - ptr1[r1]
    p2 = start[r2] + n1[r2] + np.arange(len(r2)) - ptr2[r2]
    idx[p1], val[p1], idx[p2], val[p2] = idx1, val1, idx2, val2
    return start, idx, val


def build_arrays(inst: PlatformInstance, objective: str = "variants", *, max_variants: dict | None = None,
                 budget: float | None = None, allow_unserved: bool = False) -> MilpArrays:
    """The model of :func:`build_model` (the same variables, constraints, coefficients and ``size``) built from
    ``inst``'s arrays without Pyomo: for a 1,000-application portfolio Pyomo's build and appsi's translation cost
    several times HiGHS's own solve. ``tests/test_platform.py`` holds the two builds to the same HiGHS model.

    >>> inst = PlatformInstance(family_names=["f"], part_family=np.array([0, 0]), part_weight=np.ones(2),
    ...     part_fixed_cost=np.zeros(2), pattern_ptr=np.array([0, 1, 2]), pattern_parts=np.array([0, 1]), n_apps=1,
    ...     core_app=np.array([0]), core_pattern=np.array([0]), core_cost=np.zeros(1), row_app=np.array([0]),
    ...     row_sub=np.array([0]), row_core_ptr=np.array([0, 1]), row_core=np.array([0]),
    ...     row_opt_ptr=np.array([0, 1]), row_opt_pattern=np.array([1]), row_opt_cost=np.zeros(1))
    >>> a = build_arrays(inst)            # columns x0 z0 y0 y1; rows assign, flow, core_link, option_link
    >>> a.y_col.tolist(), a.row_start.tolist(), a.row_index.tolist(), a.row_value.tolist()
    ([2, 3], [0, 1, 3, 5, 7], [0, 0, 1, 0, 2, 1, 3], [1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0])
    """
    if objective not in ("variants", "cost"):
        raise ValueError(f"objective must be 'variants' or 'cost', got {objective!r}")
    J, C, R, A = inst.n_parts, len(inst.core_app), len(inst.row_app), int(inst.n_apps)
    n_z = int(inst.row_opt_ptr[-1])
    c_item, c_part = _expand(inst.pattern_ptr, inst.pattern_parts, inst.core_pattern)
    z_item, z_part = _expand(inst.pattern_ptr, inst.pattern_parts, inst.row_opt_pattern)
    br = _breaks(inst, objective, c_item, c_part, z_item, z_part)
    nb = len(br) if br else 0
    X0, Z0, Y0, E0 = 0, C, C + n_z, C + n_z + J       # variable keys: x_c, z_i, y_j, e_a, s_e, b_e
    S0 = E0 + (A if allow_unserved else 0)
    B0 = S0 + nb
    in_use = np.zeros(J, bool)
    in_use[c_part] = True
    in_use[z_part] = True
    ar = np.arange
    blocks = []                                       # (ptr, keys, values, lower, upper) per constraint family
    nnz = 0
    # assign: the cores of a, then e_a
    app_ptr = np.searchsorted(inst.core_app, ar(A + 1)).astype(np.int64)
    e_ptr = ar(A + 1) if allow_unserved else np.zeros(A + 1, np.int64)
    e_key = E0 + ar(A) if allow_unserved else np.zeros(0, np.int64)
    blocks.append((*_rows(app_ptr, X0 + ar(C), np.ones(C), e_ptr, e_key, np.ones(len(e_key))), 1.0, 1.0))
    nnz += C + (A if allow_unserved else 0)
    # flow: the cores of r (+1), then its options (-1)
    blocks.append((*_rows(np.asarray(inst.row_core_ptr, np.int64), X0 + np.asarray(inst.row_core, np.int64),
                          np.ones(len(inst.row_core)), np.asarray(inst.row_opt_ptr, np.int64), Z0 + ar(n_z),
                          -np.ones(n_z)), 0.0, 0.0))
    nnz += int(inst.row_core_ptr[-1]) + n_z
    # core_link and option_link: the members of a group (+1), then the group's y (-1)
    z_row = np.repeat(ar(R), np.diff(inst.row_opt_ptr))[z_item]
    for keys, item, part, base in ((inst.core_app[c_item].astype(np.int64) * J + c_part, c_item, c_part, X0),
                                   ((inst.row_app[z_row].astype(np.int64) * 64 + inst.row_sub[z_row]) * J + z_part,
                                    z_item, z_part, Z0)):
        order, ptr = _group_rows(keys)
        g = len(ptr) - 1
        blocks.append((*_rows(ptr, base + item[order], np.ones(len(order)), ar(g + 1),
                              Y0 + part[order[ptr[:-1]]], -np.ones(g)), -np.inf, 0.0))
        nnz += len(item) + g
    if br:
        # the volume V_j of each break's part: its cores (x), then its option entries (z), at -volume
        cn = (br.core_ptr[1:] - br.core_ptr[:-1])[br.part]
        on = (br.opt_ptr[1:] - br.opt_ptr[:-1])[br.part]
        vptr = np.concatenate([[0], np.cumsum(cn + on)]).astype(np.int64)
        cpos = np.repeat(br.core_ptr[br.part], cn) + ar(int(cn.sum())) - np.repeat(np.cumsum(cn) - cn, cn)
        opos = np.repeat(br.opt_ptr[br.part], on) + ar(int(on.sum())) - np.repeat(np.cumsum(on) - on, on)
        vstart, vkey, vval = _rows(np.concatenate([[0], np.cumsum(cn)]).astype(np.int64), X0 + br.core[cpos],
                                   -br.core_vol[cpos], np.concatenate([[0], np.cumsum(on)]).astype(np.int64),
                                   Z0 + br.opt[opos], -br.opt_vol[opos])
        one = ar(nb + 1)
        blocks.append((*_rows(one, S0 + ar(nb), np.ones(nb), vstart, vkey, vval), -np.inf, 0.0))        # pool
        blocks.append((*_rows(one, S0 + ar(nb), np.ones(nb), one, B0 + ar(nb), -br.vmax), -np.inf, 0.0))  # break_on
        blocks.append((*_rows(one, B0 + ar(nb), br.qty, vstart, vkey, vval), -np.inf, 0.0))           # break_reach
        nnz += 2 * (nb + int(vptr[-1])) + 2 * nb
    fam_idx = {n: i for i, n in enumerate(inst.family_names)}
    for f, n in (max_variants or {}).items():
        if f not in fam_idx:
            raise ValueError(f"max_variants: unknown family {f!r}; families: {list(inst.family_names)}")
        js = np.flatnonzero((inst.part_family == fam_idx[f]) & in_use)
        nnz += len(js)
        if len(js) > int(n):
            blocks.append((np.array([0, len(js)]), Y0 + js, np.ones(len(js)), -np.inf, float(int(n))))
    if budget is not None:
        js = np.flatnonzero(in_use)
        blocks.append((np.array([0, len(js)]), Y0 + js, inst.part_weight[js].astype(float), -np.inf, float(budget)))
        nnz += len(js)
    starts = np.cumsum([0] + [int(b[0][-1]) for b in blocks])
    row_start = np.concatenate([b[0][:-1] + s for b, s in zip(blocks, starts)] + [starts[-1:]]).astype(np.int64)
    keys = np.concatenate([b[1] for b in blocks]).astype(np.int64)
    values = np.concatenate([b[2] for b in blocks]).astype(float)
    n_rows = [len(b[0]) - 1 for b in blocks]
    row_lower = np.repeat([b[3] for b in blocks], n_rows).astype(float)
    row_upper = np.repeat([b[4] for b in blocks], n_rows).astype(float)
    # objective, by variable key
    cost = np.zeros(B0 + nb)
    if objective == "variants":
        cost[Y0:E0] = np.where(in_use, inst.part_weight, 0.0)
        pen = float(np.sum(inst.part_weight[in_use])) + 1.0
    else:
        cost[Y0:E0] = np.where(in_use, inst.part_fixed_cost, 0.0)
        cost[X0:Z0], cost[Z0:Y0] = inst.core_cost, inst.row_opt_cost
        if br:
            cost[S0:B0] = -br.step
        pen = float(np.sum(inst.part_fixed_cost[in_use]) + np.sum(np.abs(inst.core_cost))
                    + np.sum(np.abs(inst.row_opt_cost))) + 1.0
    if allow_unserved:
        cost[E0:S0] = pen
    # columns in the order of first appearance (appsi's), then variables only the objective names
    uniq, first = np.unique(keys, return_index=True)
    order = uniq[np.argsort(first, kind="stable")]
    rest = np.setdiff1d(np.flatnonzero(cost), order)
    order = np.concatenate([order, rest]).astype(np.int64)
    col_of = np.full(len(cost), -1, np.int64)
    col_of[order] = ar(len(order))
    y_col = np.where(in_use, col_of[Y0:E0], -1)
    n_var = int(in_use.sum()) + C + n_z + (A if allow_unserved else 0) + 2 * nb
    upper = np.ones(len(cost))
    if br:
        upper[S0:B0] = br.vmax
    integer = ((order >= Y0) & (order < E0)) | (order >= B0)
    if br:
        integer |= np.r_[br.x_int, br.z_int, np.zeros(len(cost) - Y0, bool)][order]
    return MilpArrays(
        col_lower=np.zeros(len(order)), col_upper=upper[order], col_cost=cost[order],
        col_integer=integer, row_lower=row_lower, row_upper=row_upper, row_start=row_start,
        row_index=col_of[keys], row_value=values, y_col=y_col, x_col=col_of[X0:Z0], z_col=col_of[Z0:Y0],
        sb_col=col_of[S0:B0 + nb],
        e_col=col_of[E0:S0] if allow_unserved else None,
        size={"variables": n_var, "binaries": int(in_use.sum()) + (nb + int(br.x_int.sum() + br.z_int.sum()) if nb else 0),
              "constraints": int(sum(n_rows)), "nonzeros": int(nnz)})


@contextmanager
def _quiet_stdout():
    """Standard output (the file descriptor, where HiGHS's C++ writes) sent to the null device meanwhile: what
    Pyomo's ``capture_output(capture_fd=True)`` did here, without importing Pyomo (and SciPy's statistics with it)
    on the arrays path."""
    sys.stdout.flush()
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):   # no real descriptor (a captured stream): nothing to silence
        yield
        return
    saved = os.dup(fd)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), fd)
            try:
                yield
            finally:
                os.dup2(saved, fd)
    finally:
        os.close(saved)


def highs_model(arr: MilpArrays):
    """A silent ``highspy.Highs`` holding ``arr``, loaded by the calls appsi's HiGHS interface makes (variables,
    their integrality, the rows, the objective), so it holds the model appsi would hand over."""
    import highspy
    with _quiet_stdout():           # HiGHS prints its banner on stdout when the first one is made
        h = highspy.Highs()
    h.setOptionValue("output_flag", False)
    n = len(arr.col_cost)
    kind = highspy.HighsVarType
    h.addVars(n, arr.col_lower, arr.col_upper)
    h.changeColsIntegrality(n, np.arange(n), np.array([kind.kInteger if b else kind.kContinuous
                                                       for b in arr.col_integer]))
    h.addRows(len(arr.row_lower), arr.row_lower, arr.row_upper, len(arr.row_index), arr.row_start[:-1],
              arr.row_index, arr.row_value)
    h.changeObjectiveOffset(0.0)
    h.changeObjectiveSense(highspy.ObjSense.kMinimize)
    h.changeColsCost(n, np.arange(n), arr.col_cost)
    return h


def designs_start(inst: PlatformInstance, y: np.ndarray) -> tuple:
    """``(x, z, s, b)``: a complete MIP start from platform ``y`` where the MILP has volume breaks (a platform alone
    leaves the integral ``x`` and ``z`` to find): each application's cheapest design on it at the unit costs (the
    first core of equal cost, each row's first cheapest option), the breaks its volumes reach."""
    y = np.asarray(y, bool)
    pid = np.repeat(np.arange(inst.n_patterns), inst.pattern_len())
    ok = np.bincount(pid, weights=y[inst.pattern_parts].astype(float), minlength=inst.n_patterns) \
        >= inst.pattern_len() - 0.5
    R, C, n_z = len(inst.row_app), len(inst.core_app), int(inst.row_opt_ptr[-1])
    val = np.where(ok[inst.row_opt_pattern], inst.row_opt_cost, np.inf)
    best, pick = np.full(R, np.inf), np.full(R, -1)
    for r in range(R):
        lo, hi = inst.row_opt_ptr[r], inst.row_opt_ptr[r + 1]
        if hi > lo:
            k = int(np.argmin(val[lo:hi]))
            if np.isfinite(val[lo + k]):
                best[r], pick[r] = val[lo + k], lo + k
    core_val = np.where(ok[inst.core_pattern], inst.core_cost, np.inf)
    r_of = np.repeat(np.arange(R), np.diff(inst.row_core_ptr))
    np.add.at(core_val, inst.row_core, best[r_of])
    x, z = np.zeros(C), np.zeros(n_z)
    start = np.searchsorted(inst.core_app, np.arange(inst.n_apps + 1))
    for a in range(inst.n_apps):
        if start[a + 1] > start[a]:
            c = start[a] + int(np.argmin(core_val[start[a]:start[a + 1]]))
            if np.isfinite(core_val[c]):
                x[c] = 1.0
    rows = r_of[x[inst.row_core] > 0.5]
    z[pick[rows]] = 1.0
    c_item, c_part = _expand(inst.pattern_ptr, inst.pattern_parts, inst.core_pattern)
    z_item, z_part = _expand(inst.pattern_ptr, inst.pattern_parts, inst.row_opt_pattern)
    br = _breaks(inst, "cost", c_item, c_part, z_item, z_part)
    if br is None:
        return x, z, np.zeros(0), np.zeros(0)
    vol = np.zeros(inst.n_parts)
    for e in range(len(br)):
        cs, cv, zs, zv = br.terms(e)
        vol[br.part[e]] = float(np.dot(cv, x[cs]) + np.dot(zv, z[zs]))
    b = (vol[br.part] >= br.qty - 1e-9).astype(float)
    return x, z, b * vol[br.part], b


def _highs_options(time_limit: float, mip_gap: float, node_limit: int | None) -> dict:
    """The HiGHS options of a solve, on both builds: the limits, the gap, one thread (:data:`HIGHS_THREADS`)."""
    opts = {"time_limit": float(time_limit), "mip_rel_gap": float(mip_gap), "threads": HIGHS_THREADS}
    if node_limit is not None:
        opts["mip_max_nodes"] = int(node_limit)
    return opts


def _run_highs(run) -> None:
    """``run()`` (a solve; returns its ``highspy.Highs``), again once after HiGHS's thread pool is rebuilt if HiGHS
    refused to start: the pool is one per process, made at the first solve with that solve's ``threads``, and a later
    solve asking for another count stops with an error before it begins (another HiGHS user in the process, e.g. a
    design solver through Pyomo, may have made it with HiGHS's default)."""
    import highspy
    if run().getModelStatus() == highspy.HighsModelStatus.kNotset:
        highspy.Highs.resetGlobalScheduler(True)
        run()


def _highs_arrays(arr: MilpArrays, time_limit: float, mip_gap: float, warm_start: np.ndarray | None,
                  full: tuple | None = None, node_limit: int | None = None):
    """Solve ``arr`` with highspy, with appsi's options and MIP start; returns ``(status, has a solution,
    objective, bound, column values, nodes)``, read as appsi's ``_postsolve`` reads them."""
    import highspy
    h = highs_model(arr)
    n = len(arr.col_cost)
    for k, v in _highs_options(time_limit, mip_gap, node_limit).items():
        h.setOptionValue(k, v)
    if warm_start is not None:
        col = np.zeros(n)
        has = arr.y_col >= 0
        col[arr.y_col[has]] = np.asarray(warm_start, bool)[has].astype(float)
        if full is not None:   # the designs too (volume breaks: integral x and z)
            x, z, s, b = full
            col[arr.x_col], col[arr.z_col], col[arr.sb_col] = x, z, np.r_[s, b]
        start = highspy.HighsSolution()
        start.col_value = col
        start.value_valid = True
        start.dual_valid = False
        h.setSolution(start)
    h.HandleKeyboardInterrupt = True
    _run_highs(lambda: (h.run(), h)[1])
    ms = highspy.HighsModelStatus
    st = h.getModelStatus()
    # kSolutionLimit: HiGHS's MIP limits, of which only mip_max_nodes is set
    status = {ms.kOptimal: "optimal", ms.kTimeLimit: "time_limit", ms.kSolutionLimit: "node_limit",
              ms.kInfeasible: "infeasible", ms.kUnboundedOrInfeasible: "infeasible"}.get(st, "error")
    sol = h.getSolution()
    limits = {ms.kObjectiveBound, ms.kObjectiveTarget, ms.kTimeLimit, ms.kIterationLimit,
              getattr(ms, "kSolutionLimit", ms.kIterationLimit)}
    has = st == ms.kOptimal or (st in limits and sol.value_valid)
    info = h.getInfo()
    obj = float(info.objective_function_value) if has else np.nan
    if info.mip_node_count == -1:
        bound = obj
    else:
        bound = float(info.mip_dual_bound)
    return status, has, obj, bound, np.asarray(sol.col_value) if has else None, int(info.mip_node_count)


def _result_values(res):
    bound = getattr(res, "best_objective_bound", None)
    feas = getattr(res, "best_feasible_objective", None)
    return (np.nan if feas is None else float(feas)), (np.nan if bound is None else float(bound))


def solve(inst: PlatformInstance, objective: str = "variants", *, solver: str = "highs",
          time_limit: float = TIME_LIMIT_S, node_limit: int | None = NODE_LIMIT,
          mip_gap: float = 0.0, max_variants: dict | None = None, budget: float | None = None,
          allow_unserved: bool = False, warm_start: np.ndarray | None = None, model=None,
          build: str = "arrays") -> PlatformSolution:
    """Build (unless ``model`` is given) and solve; ``warm_start``: a bool platform (e.g. the greedy one).

    ``status`` is ``optimal`` (gap within ``mip_gap``), ``node_limit`` (``node_limit`` branch-and-bound nodes
    taken: the best platform found in them, gap reported; the same on every run), ``time_limit`` (``time_limit``
    wall-clock seconds passed first: the best platform found, gap reported, which depends on the machine and its
    load), ``infeasible`` or ``error``. ``node_limit`` None: no node limit. HiGHS runs on :data:`HIGHS_THREADS`
    thread. ``build`` (:data:`BUILDS`): HiGHS gets the model from
    :func:`build_arrays` through highspy (``arrays``, the default) or from :func:`build_model` through Pyomo
    (``pyomo``: the reference; SCIP and a given ``model`` always take it). Both hand HiGHS the same model.
    """
    if solver not in SOLVERS:
        raise ValueError(f"solver must be one of {sorted(SOLVERS)}, got {solver!r}")
    if build not in BUILDS:
        raise ValueError(f"build must be one of {list(BUILDS)}, got {build!r}")
    t0 = time.perf_counter()
    if inst.n_apps == 0:                       # nothing to serve: the empty platform
        return PlatformSolution("optimal", np.zeros(inst.n_parts, bool), 0.0, 0.0, 0.0, 0.0, 0.0,
                                {"variables": 0, "binaries": 0, "constraints": 0, "nonzeros": 0}, solver)
    if solver == "highs" and build == "arrays" and model is None:
        arr = build_arrays(inst, objective, max_variants=max_variants, budget=budget, allow_unserved=allow_unserved)
        t1 = time.perf_counter()
        full = designs_start(inst, warm_start) if warm_start is not None and objective == "cost" \
            and inst.n_breaks else None
        status, has, obj, bound, col, nodes = _highs_arrays(arr, time_limit, mip_gap, warm_start, full, node_limit)
        y = unserved = x = z = None
        if has:
            y = np.zeros(inst.n_parts, bool)
            y[arr.y_col >= 0] = col[arr.y_col[arr.y_col >= 0]] > 0.5
            if allow_unserved:
                unserved = col[arr.e_col] > 0.5
            if objective == "cost" and inst.n_breaks:
                x, z = col[arr.x_col] > 0.5, col[arr.z_col] > 0.5
        return PlatformSolution(status=status, y=y, objective=obj, bound=bound, gap=_gap(has, obj, bound, status),
                                time_s=time.perf_counter() - t1, build_s=t1 - t0, size=dict(arr.size),
                                solver=solver, unserved=unserved, x=x, z=z, nodes=nodes)
    import pyomo.environ as pyo
    m = model if model is not None else build_model(inst, objective, max_variants=max_variants, budget=budget,
                                                    allow_unserved=allow_unserved)
    build_s = time.perf_counter() - t0
    J = inst.n_parts
    if warm_start is not None:
        for j in m.y:
            m.y[j].set_value(float(bool(warm_start[j])))
        if hasattr(m, "b"):   # volume breaks: the designs too
            x, z, s, b = designs_start(inst, warm_start)
            for vals, var in ((x, m.x), (z, m.z), (s, m.s), (b, m.b)):
                for i, v in enumerate(vals):
                    var[i].set_value(float(v))
    t1 = time.perf_counter()
    if solver == "highs":
        from pyomo.contrib.appsi.solvers import Highs
        from pyomo.contrib.appsi.base import TerminationCondition as TC
        opt = Highs()
        opt.config.time_limit = float(time_limit)
        opt.config.mip_gap = float(mip_gap)
        opt.config.load_solution = False
        opt.config.warmstart = warm_start is not None
        opt.highs_options = {k: v for k, v in _highs_options(time_limit, mip_gap, node_limit).items()
                             if k not in ("time_limit", "mip_rel_gap")}
        res = None

        def run():
            nonlocal res
            res = opt.solve(m)
            return opt._solver_model
        _run_highs(run)
        nodes = int(opt._solver_model.getInfo().mip_node_count)
        tc = res.termination_condition
        obj, bound = _result_values(res)
        has = res.best_feasible_objective is not None
        if has:
            res.solution_loader.load_vars()
        # maxIterations: appsi's name for HiGHS's kSolutionLimit (the MIP limits, of which only mip_max_nodes is set)
        status = {TC.optimal: "optimal", TC.maxTimeLimit: "time_limit", TC.maxIterations: "node_limit",
                  TC.infeasible: "infeasible", TC.infeasibleOrUnbounded: "infeasible"}.get(tc, "error")
    else:
        opt = pyo.SolverFactory(SOLVERS[solver])
        opts = {"limits/time": float(time_limit), "limits/gap": float(mip_gap)}
        if node_limit is not None:
            opts["limits/nodes"] = int(node_limit)
        if hasattr(opt, "warm_start_capable") and "warmstart_discrete_vars" in getattr(opt, "config", {}):
            # Pyomo >= 6.10: scip_direct is the new interface behind the legacy one, whose solve takes no warmstart
            opt.config.warmstart_discrete_vars = warm_start is not None
            res = opt.solve(m, options=opts, load_solutions=False)
        else:
            res = opt.solve(m, options=opts, load_solutions=False, warmstart=warm_start is not None)
        tc = str(res.solver.termination_condition).split(".")[-1]
        nodes = -1
        has = len(res.solution) > 0
        if has:
            m.solutions.load_from(res)
        status = {"optimal": "optimal", "maxTimeLimit": "time_limit", "maxIterations": "node_limit",
                  "infeasible": "infeasible"}.get(tc, "error")
        obj = float(pyo.value(m.obj)) if has else np.nan
        lb = res.problem.lower_bound
        bound = float(lb) if lb is not None and np.isfinite(float(lb)) else np.nan
    solve_s = time.perf_counter() - t1
    y = None
    if has:
        y = np.zeros(J, bool)
        for j in m.y:
            y[j] = (pyo.value(m.y[j]) or 0.0) > 0.5
    unserved = x = z = None
    if has and allow_unserved:
        unserved = np.array([(pyo.value(m.e[a]) or 0.0) > 0.5 for a in range(inst.n_apps)], bool)
    if has and hasattr(m, "b"):
        x = np.array([(pyo.value(m.x[c]) or 0.0) > 0.5 for c in range(len(inst.core_app))], bool)
        z = np.array([(pyo.value(m.z[i]) or 0.0) > 0.5 for i in range(int(inst.row_opt_ptr[-1]))], bool)
    return PlatformSolution(status=status, y=y, objective=obj, bound=bound, gap=_gap(has, obj, bound, status),
                            time_s=solve_s, build_s=build_s, size=dict(m.size), solver=solver, unserved=unserved,
                            x=x, z=z, nodes=nodes)


def _gap(has: bool, obj: float, bound: float, status: str) -> float:
    """Relative gap between the platform found and the bound (0 for an optimum without a bound, else NaN)."""
    if has and np.isfinite(obj) and np.isfinite(bound):
        return abs(obj - bound) / max(abs(obj), 1e-9)
    return 0.0 if status == "optimal" else np.nan
