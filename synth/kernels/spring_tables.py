"""Main-spring tables for many keys x many options: the keys and options the kernels read (what depends on a key
alone or an option alone, computed once by the reference functions), and every margin of keys x options or of listed
pairs (:func:`margins`, :func:`pair_margins`) on the compiled kernels or the numpy twin (the registry's spring group).

The scans over these tables (first feasible, any feasible, max-min) are :mod:`synth.kernels.main_spring`'s; its
docstring states the registry semantics and the exactness both share.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from synth.design import evaluate
from synth.design.combine import near_figures
from synth.design.constraints import FEAS_TOL, REGISTRY, by_group, margin as registry_margin
from synth.design.settings import DEFAULT, Settings
from synth.errors import InputError, Problem
from synth.kernels import engines
from synth.kernels.numba_setup import Compiled
from synth.model import torsion_spring
from synth.design.space import space

__all__ = ["MARGIN_NAMES", "checks", "compiled_covers", "ENGINES", "OPTION_FIELDS", "load_kernels", "load_scans", "load_rounds", "numba_loaded",
           "SpringOptions", "SpringKeys", "spring_options", "options_of_space", "spring_keys", "keys_of_rows",
           "kernel_tables", "check_engine", "same_constants", "reference_margins", "margins", "near_above",
           "pair_margins"]

#: the margins the compiled kernels compute, in their layout: the registry's non-advisory spring constraints of
#: step 9 as declared (a check added later with ``register`` is not among them: see :func:`checks`)
MARGIN_NAMES = engines.SPRING_MARGINS
_DECLARED = tuple(c.id for c in by_group("spring") if not c.advisory)
if not set(MARGIN_NAMES) <= set(_DECLARED):  # pragma: no cover - a kernel margin the registry no longer declares
    raise ImportError(f"synth.kernels.main_spring computes {MARGIN_NAMES}; the registry's spring group is "
                      f"{_DECLARED}: remove the constraint from the kernels (and their tests)")


def checks() -> tuple:
    """The margins every function of this module returns, in their column order: :data:`MARGIN_NAMES`, then each
    non-advisory spring check the registry holds beyond them (one added with ``register``), read now.

    The compiled kernels compute :data:`MARGIN_NAMES` only; while the registry holds another spring check every
    call runs on the numpy twin (the registry's own group, :func:`compiled_covers`), so a new check needs a
    registry entry and a physics function, never a kernel edit (it costs the kernels' speed until they learn it).
    """
    extra = tuple(c.id for c in by_group("spring") if not c.advisory and c.id not in MARGIN_NAMES)
    return MARGIN_NAMES + extra


def compiled_covers(settings: Settings = DEFAULT) -> bool:
    """Whether the compiled kernels compute the registry's spring judgement under ``settings`` (else the numpy twin
    runs): :func:`synth.kernels.engines.spring_covers`, the one decision."""
    return engines.spring_covers(settings)
ENGINES = engines.ENGINES
#: the option columns the numpy twin reads (the space's spring table names them so)
OPTION_FIELDS = evaluate.SPRING_OPTION_COLUMNS


def _import_kernels():
    from synth.kernels import _main_spring_jit
    return _main_spring_jit


def _import_scans():
    from synth.kernels import _main_spring_scans_jit
    return _main_spring_scans_jit


def _import_rounds():
    from synth.kernels import _main_spring_rounds_jit
    return _main_spring_rounds_jit


#: the compiled kernels modules, each imported (numba with it) on its first call, later calls an attribute lookup:
#: the pair physics and margin tables, the searches (first feasible, max-min, list order) and the platform's rounds
load_kernels = Compiled(_import_kernels)
load_scans = Compiled(_import_scans)
load_rounds = Compiled(_import_rounds)


def numba_loaded() -> bool:
    """Whether this process has loaded a compiled kernels module of the main spring (and so imported numba) yet."""
    return any(k.loaded() for k in (load_kernels, load_scans, load_rounds))


# --------------------------------------------------------------------------------------- inputs


def _arr(name, x, n, positive=False):
    a = np.asarray(x, dtype=float).reshape(-1)
    if a.size == 1:
        a = np.full(n, a[0])
    bad = ~np.isfinite(a) | (a <= 0) if positive else ~np.isfinite(a)
    if bad.any():
        raise InputError(Problem(name, float(a[np.flatnonzero(bad)[0]]), "a finite number" + (" > 0" if positive else "")))
    return a


def _bools(name, x, n, accepted):
    a = np.asarray(x).reshape(-1)
    if a.dtype != bool:
        raise InputError(Problem(name, a[:1].tolist(), accepted))
    return np.full(n, a[0]) if a.size == 1 else a


def _length(fields: dict) -> int:
    sizes = {k: int(np.size(v)) for k, v in fields.items()}
    n = max(sizes.values())
    for k, size in sizes.items():
        if size not in (1, n):
            raise InputError(Problem(k, f"{size} values", f"1 or {n} values (one per row)"))
    return n


def _scale(limit):
    """The registry's default scale of a margin: ``|limit|``, or 1 where it is zero (:func:`registry_margin`)."""
    a = np.abs(np.asarray(limit, dtype=float))
    return np.where(a > 0, a, 1.0)


@dataclass(frozen=True, eq=False)
class SpringOptions:
    """Main-spring options: the raw per-option columns (:data:`OPTION_FIELDS`) and the option-only quantities
    the kernels read."""

    raw: dict          # the columns of the space's spring table the group reads
    derived: dict      # the columns of _main_spring_jit.OPTION_COLUMNS, by name
    upper_bound: np.ndarray  # smallest option-only margin (index, section; NaN as -inf): bounds the smallest margin
    constants: dict    # main_spring_constants() when built
    _table: dict = field(default_factory=dict, repr=False)

    def __len__(self) -> int:
        return len(self.upper_bound)

    def take(self, idx) -> "SpringOptions":
        """The options ``idx`` (indices or a boolean mask), as a new :class:`SpringOptions`."""
        return SpringOptions({k: v[idx] for k, v in self.raw.items()}, {k: v[idx] for k, v in self.derived.items()},
                             self.upper_bound[idx], self.constants)


def _options(raw: dict) -> SpringOptions:
    cst = torsion_spring.main_spring_constants()
    b, h, rnd = raw["b_mm"], raw["h_mm"], raw["round_wire"]
    mbd, sy = raw["main_spring_mean_body_diameter_mm"], raw["sigma_y_mpa"]
    c = torsion_spring.spring_index(mbd, b, h, rnd)
    reg = REGISTRY
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        d = {
            "ei": raw["E_mpa"] * torsion_spring.second_moment_mm4(b, h, rnd), "mbd": mbd, "kf": torsion_spring.curvature_factor(c, "inner"),
            "z": torsion_spring.section_modulus_mm3(b, h, rnd), "rm": raw["Rm_mpa"], "sa0": raw["sigma_A0_mpa"], "sy": sy,
            "sy_scale": _scale(sy), "h": h, "h_tol": raw["h_tol_mm"], "bb": b + raw["b_tol_mm"],
            "b_scale": np.where(b > 0, b, 1.0),
            "idx_min": registry_margin(reg["spring_index_min"], c, cst["main_spring_index_min"]),
            "idx_max": registry_margin(reg["spring_index_max"], c, cst["main_spring_index_max"]),
            "sec": registry_margin(reg["spring_material_section"], raw["supplied_in_section"].astype(float), 1.0),
        }
    d = {k: np.ascontiguousarray(np.broadcast_to(np.asarray(v, dtype=float), mbd.shape)) for k, v in d.items()}
    ub = np.minimum(np.minimum(d["idx_min"], d["idx_max"]), d["sec"])
    d["ub"] = np.where(np.isnan(ub), -np.inf, ub)
    return SpringOptions(raw, d, d["ub"], cst)


def spring_options(*, E_mpa, Rm_mpa, sigma_y_mpa, sigma_A0_mpa, b_mm, h_mm, round_wire, mbd_mm, b_tol_mm=0.0,
                   h_tol_mm=0.0, sigma_perm_static_mpa=np.nan, supplied_in_section=True) -> SpringOptions:
    """Main-spring options from per-option arguments (as ``main_spring_design`` names them, broadcast).

    Computes with the reference functions what depends on the option alone:
    ``E I`` (eq. 64-65), the section modulus (eq. 73/76), the curvature
    factor (eq. 74) at the index (eq. 75/77), the registry margins of the
    index range (EN 13906-3, ``constants_main_spring.csv``) and of the
    material's wire section, ``b + b_tol`` and the scales of the margins.
    ``sigma_perm_static_mpa`` only feeds the advisory static check (not a
    kernel margin).
    """
    fields = dict(E_mpa=E_mpa, Rm_mpa=Rm_mpa, sigma_y_mpa=sigma_y_mpa, sigma_A0_mpa=sigma_A0_mpa, b_mm=b_mm,
                  h_mm=h_mm, round_wire=round_wire, b_tol_mm=b_tol_mm, h_tol_mm=h_tol_mm,
                  main_spring_mean_body_diameter_mm=mbd_mm, sigma_perm_static_mpa=sigma_perm_static_mpa,
                  supplied_in_section=supplied_in_section)
    n = _length(fields)
    raw = {k: _arr(k if k != "main_spring_mean_body_diameter_mm" else "mbd_mm", v, n,
                   positive=not k.endswith("_tol_mm"))
           for k, v in fields.items() if k not in ("round_wire", "supplied_in_section", "sigma_perm_static_mpa")}
    raw["round_wire"] = _bools("round_wire", round_wire, n, "True (round) or False (rectangular) per option")
    raw["supplied_in_section"] = _bools("supplied_in_section", supplied_in_section, n, "True or False per option")
    sp = np.asarray(sigma_perm_static_mpa, dtype=float).reshape(-1)
    raw["sigma_perm_static_mpa"] = np.full(n, sp[0]) if sp.size == 1 else sp
    return _options(raw)


_SPACE_OPTIONS: dict = {}


def options_of_space(table: dict | None = None, idx=None) -> SpringOptions:
    """:class:`SpringOptions` of a design space's spring table (default: :func:`synth.design.space.space`'s;
    ``idx``: a subset of its rows). The whole table's is kept per table and catalog constants (its yield
    thresholds too)."""
    if table is None:
        table = space().tables["spring"]
    if idx is None:
        hit = _SPACE_OPTIONS.get(id(table))
        if hit is not None and hit[0] is table and hit[1].constants == torsion_spring.main_spring_constants():
            return hit[1]
        opts = options_of_space(table, np.arange(len(table["b_mm"])))
        _SPACE_OPTIONS.clear()
        _SPACE_OPTIONS[id(table)] = (table, opts)
        return opts
    raw = {k: np.asarray(table[k])[idx] for k in OPTION_FIELDS}
    raw["round_wire"] = raw["round_wire"].astype(bool)
    raw["supplied_in_section"] = raw["supplied_in_section"].astype(bool)
    for k in OPTION_FIELDS:
        if k not in ("round_wire", "supplied_in_section"):
            raw[k] = raw[k].astype(float)
    return _options(raw)


@dataclass(frozen=True, eq=False)
class SpringKeys:
    """Spring keys: the raw per-key inputs (:data:`synth.design.evaluate.SPRING_INPUTS` and ``fatigue_verified``)
    and the key-only quantities the kernels read; for keys of the evaluator's rows (:func:`keys_of_rows`), their
    applications (``apps``, each key's ``app``) and the other core values a registered spring check reads
    (``core``: :func:`synth.design.evaluate.core_values`), which the numpy twin hands to the registry's group."""

    raw: dict
    derived: dict      # the columns of _main_spring_jit.KEY_COLUMNS, by name
    consts: dict       # the scalars of _main_spring_jit.CONST_NAMES
    constants: dict    # main_spring_constants() when built
    _table: dict = field(default_factory=dict, repr=False)
    apps: object = field(default=None, repr=False)
    app: np.ndarray | None = field(default=None, repr=False)
    core: dict = field(default_factory=dict, repr=False)

    def __len__(self) -> int:
        return len(self.derived["k180"])

    def take(self, idx) -> "SpringKeys":
        """The keys ``idx`` (indices or a boolean mask), as a new :class:`SpringKeys`."""
        return SpringKeys({k: v[idx] for k, v in self.raw.items()}, {k: v[idx] for k, v in self.derived.items()},
                          self.consts, self.constants, apps=self.apps,
                          app=None if self.app is None else self.app[idx],
                          core={k: v[idx] for k, v in self.core.items()})


def _keys(raw: dict, apps=None, app=None, core=None) -> SpringKeys:
    cst = torsion_spring.main_spring_constants()
    k = raw["stiffness_nm_per_deg"]
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        ang = torsion_spring.working_angles_deg(raw["spring_torque_nominal_nm"], raw["torque_tolerance_pct"], k,
                                    raw["theta_pp_deg"], raw["dtheta_inst_nom_deg"], raw["dtheta_nom_free_arm_deg"])
        outer_min = raw["housing_outer_diameter_mm"] - cst["spring_housing_outer_tol_mm"]
        inner_max = raw["housing_inner_diameter_mm"] + cst["spring_housing_inner_tol_mm"]
        d = {
            "k180": 180.0 * np.maximum(k * 1000.0, 1e-12), "t_plus": torsion_spring.torque_nm(ang["theta_plus"], k),
            "t_minus": torsion_spring.torque_nm(ang["theta_minus"], k), "t_inst": torsion_spring.torque_nm(ang["theta_inst"], k),
            "inc_inst": 1.0 * ang["theta_inst"] / 360.0, "inc_free_arm": 1.0 * ang["theta_free_arm"] / 360.0,
            "inc_nom": 1.0 * ang["theta_nom"] / 360.0, "height": raw["housing_height_mm"],
            "outer_min": outer_min, "outer_scale": _scale(outer_min), "inner_max": inner_max,
            "inner_scale": _scale(inner_max), "winding": np.ones(len(k)),
            "fatigue": raw["fatigue_verified"].astype(float),
        }
    d = {name: np.ascontiguousarray(np.asarray(v, dtype=float)) for name, v in d.items()}
    sf_min = cst["main_spring_min_safety_factor"]
    consts = {"mbd_tol": cst["main_spring_mbd_tol_mm"], "sf_min": sf_min, "sf_scale": float(_scale(sf_min)),
              "min_gap": cst["main_spring_min_coil_gap_mm"]}
    return SpringKeys(raw, d, consts, cst, apps=apps, app=app, core=core or {})


def spring_keys(*, spring_torque_nominal_nm, housing_height_mm, housing_outer_diameter_mm, housing_inner_diameter_mm,
                stiffness_nm_per_deg, torque_tolerance_pct, theta_pp_deg, dtheta_inst_nom_deg=None,
                dtheta_nom_free_arm_deg=None, fatigue_verified=True) -> SpringKeys:
    """Spring keys from per-key arguments (as ``main_spring_design`` names them, broadcast).

    Computes with the reference functions what depends on the key alone: the
    working angles (eq. 66-70), the torques at theta+, theta- and
    installation (eq. 71), the coil increments ``theta/360`` (eq. 78, the
    winding spring of the evaluator), ``180 k_t`` (eq. 64-65) and the housing
    limits with their tolerances (eq. 82, 86). Missing travels take their
    documented defaults (:data:`synth.design.applications.DEFAULTS`).
    ``fatigue_verified=False``: no durability test, the fatigue margin is ``+inf``.
    """
    cst = torsion_spring.main_spring_constants()
    if dtheta_inst_nom_deg is None:
        dtheta_inst_nom_deg = cst["main_spring_dtheta_inst_nom_deg"]
    if dtheta_nom_free_arm_deg is None:
        dtheta_nom_free_arm_deg = cst["main_spring_dtheta_nom_free_arm_deg"]
    fields = dict(spring_torque_nominal_nm=spring_torque_nominal_nm, housing_height_mm=housing_height_mm,
                  housing_outer_diameter_mm=housing_outer_diameter_mm,
                  housing_inner_diameter_mm=housing_inner_diameter_mm, stiffness_nm_per_deg=stiffness_nm_per_deg,
                  torque_tolerance_pct=torque_tolerance_pct, theta_pp_deg=theta_pp_deg,
                  dtheta_inst_nom_deg=dtheta_inst_nom_deg, dtheta_nom_free_arm_deg=dtheta_nom_free_arm_deg,
                  fatigue_verified=fatigue_verified)
    n = _length(fields)
    raw = {k: _arr(k, v, n, positive=k == "stiffness_nm_per_deg") for k, v in fields.items()
           if k != "fatigue_verified"}
    raw["spring_torque_nominal_nm"] = np.maximum(raw["spring_torque_nominal_nm"], 1e-6)  # as the evaluator
    raw["fatigue_verified"] = _bools("fatigue_verified", fatigue_verified, n, "True or False per key")
    return _keys(raw)


def keys_of_rows(apps, keys: dict, k=None) -> SpringKeys:
    """:class:`SpringKeys` of rows ``k`` (default all) of the evaluator's keys (:func:`synth.design.evaluate.spring_keys`)
    of applications ``apps``: the inputs :func:`synth.design.evaluate.spring_inputs` gives the spring group, and
    whether the application has its durability test (the fatigue check's requirement)."""
    if k is None:
        k = np.arange(len(keys["app"]))
    raw = {name: np.ascontiguousarray(np.asarray(v, dtype=float)) for name, v in evaluate.spring_inputs(apps, keys, k).items()}
    raw["fatigue_verified"] = np.asarray(apps.met(REGISTRY["spring_fatigue"].needs[0]))[keys["app"][k]]
    core = {c: np.asarray(v)[k] for c, v in keys.items() if c != "app" and c not in evaluate.SPRING_KEY_VALUES}
    return _keys(raw, apps, np.asarray(keys["app"])[k], core)


def kernel_tables(keys: SpringKeys, options: SpringOptions):
    """The kernels' C-ordered tables of ``keys`` and ``options`` (column order of the compiled module; memoised)."""
    jit = load_kernels()
    if "t" not in options._table:
        options._table["t"] = np.ascontiguousarray(np.stack([options.derived[c] for c in jit.OPTION_COLUMNS], axis=1))
    if "t" not in keys._table:
        keys._table["t"] = np.ascontiguousarray(np.stack([keys.derived[c] for c in jit.KEY_COLUMNS], axis=1))
        keys._table["c"] = np.array([keys.consts[c] for c in jit.CONST_NAMES], dtype=float)
    return jit, keys._table["t"], options._table["t"], keys._table["c"]


def check_engine(engine, settings: Settings) -> str:
    """The engine a call runs on: ``engine`` where the one decision allows it (:func:`synth.kernels.engines.spring`:
    the numpy twin where the compiled kernels do not cover the registry's checks under ``settings``)."""
    return engines.spring(settings, engine)


def same_constants(keys: SpringKeys, options: SpringOptions):
    """Keys and options must carry the catalog constants the reference reads now (a user catalog may change them)."""
    cst = torsion_spring.main_spring_constants()
    for name, obj in (("keys", keys), ("options", options)):
        if obj.constants != cst:
            changed = sorted(k for k in cst if obj.constants.get(k) != cst[k])
            raise InputError(Problem(name, f"built with other values of {', '.join(changed)}",
                                     "keys and options built after the last change of the catalog constants"))


class _Requirements:
    """What :func:`synth.design.evaluate.finish` asks of the applications, for keys x options rows of keys made
    without their applications (:func:`spring_keys`): the durability test only (no application field)."""

    f: dict = {}  # no application field: a check whose physics reads one needs keys of rows (keys_of_rows)

    def __init__(self, fatigue_verified):
        self.fatigue_verified = fatigue_verified

    def met(self, requirement):
        if requirement != REGISTRY["spring_fatigue"].needs[0]:  # pragma: no cover - a new requirement in step 9
            raise KeyError(f"the spring kernels know the requirement of spring_fatigue only, not {requirement!r}")
        return self.fatigue_verified


def _group(keys: SpringKeys, ki: np.ndarray, values: dict, settings: Settings) -> evaluate.Group:
    """The registry's spring group (:func:`synth.design.evaluate.finish`) of rows of keys ``ki`` (flat, one per row)
    and their ``values`` (:func:`synth.design.evaluate.spring_values`): with the keys' applications where they have
    them (a check may read an application field or another core value), under ``settings``' rules."""
    if keys.apps is not None:
        apps, a = keys.apps, keys.app[ki]
    else:
        apps, a = _Requirements(keys.raw["fatigue_verified"][ki]), np.arange(len(ki))
    core = {k: v[ki] for k, v in keys.core.items()}
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return evaluate.finish("spring", values, apps, a, rules=settings.rules, core=core)


def reference_margins(keys: SpringKeys, options: SpringOptions, key_idx=None, option_idx=None, *,
                      settings: Settings = DEFAULT) -> np.ndarray:
    """Margins ``(n_keys, n_options, len(checks()))`` by the registry path itself: :func:`synth.design.evaluate.spring_values`
    on keys x options broadcast and :func:`synth.design.evaluate.finish` (optionally for the keys ``key_idx`` and
    the options ``option_idx``), under ``settings`` (its design rules, its spring limit basis)."""
    ki = np.arange(len(keys)) if key_idx is None else np.asarray(key_idx)
    oi = np.arange(len(options)) if option_idx is None else np.asarray(option_idx)
    nk, no = len(ki), len(oi)
    x = {k: v[ki][:, None] for k, v in keys.raw.items() if k != "fatigue_verified"}
    o = {k: v[oi][None, :] for k, v in options.raw.items()}
    v = evaluate.spring_values(o, x, settings)
    flat = {name: np.broadcast_to(val, (nk, no)).reshape(-1) for name, val in v.items()}
    g = _group(keys, np.repeat(ki, no), flat, settings)
    return np.stack([g.margins[m].reshape(nk, no) for m in checks()], axis=-1)


def margins(keys: SpringKeys, options: SpringOptions, *, engine: str = "numba", parallel: bool = False,
            out: np.ndarray | None = None, settings: Settings = DEFAULT) -> np.ndarray:
    """(a) Every margin, ``out[i, j, m]`` for key ``i``, option ``j`` and margin ``checks()[m]`` (>= 0 passes).

    ``engine="numpy"`` is :func:`reference_margins` itself. The array holds
    ``8 * 8`` bytes per pair: call it on chunks of keys for large tables, and
    pass ``out`` (float64, C order, ``(n_keys, n_options, 8)``) to reuse one
    buffer (numba engine). ``settings``: the configuration (design rules, limit basis) judged under.
    """
    engine = check_engine(engine, settings)
    same_constants(keys, options)
    if engine == "numpy":
        return reference_margins(keys, options, settings=settings)
    jit, kt, ot, c = kernel_tables(keys, options)
    shape = (len(keys), len(options), jit.N_MARGINS)
    if out is None:
        out = np.empty(shape)
    elif out.shape != shape or out.dtype != np.float64 or not out.flags.c_contiguous:
        raise InputError(Problem("out", f"{out.dtype} array of shape {out.shape}", f"a C-ordered float64 array {shape}"))
    (jit.margins_table_parallel if parallel else jit.margins_table)(kt, ot, c, out)
    return out


def near_above(keys: SpringKeys, options: SpringOptions, floor: float, *, engine: str = "numba",
               settings: Settings = DEFAULT) -> tuple:
    """``(low, second, failing)``, each ``(n_keys, n_options)``: the near figures of every pair whose smallest margin
    reaches ``floor`` (:func:`synth.design.combine.near_figures` of its row of :func:`margins`: the smallest, the
    second smallest, the number of failing margins); a pair below ``floor`` has ``low`` below ``floor`` (its yield
    margin or option-only bound in the compiled engine, which skips its physics) and the others undefined. The
    bulk's nearest design reads these, never the margins themselves."""
    engine = check_engine(engine, settings)
    if engine == "numpy":
        out = margins(keys, options, engine=engine, settings=settings)
        if not out.shape[2]:
            return np.full(out.shape[:2], np.inf), np.full(out.shape[:2], np.inf), np.zeros(out.shape[:2])
        a, b, f = near_figures(out.reshape(-1, out.shape[2]))
        return a.reshape(out.shape[:2]), b.reshape(out.shape[:2]), f.reshape(out.shape[:2]).astype(float)
    same_constants(keys, options)
    jit, kt, ot, c = kernel_tables(keys, options)
    low, second, failing = (np.empty((len(keys), len(options))) for _ in range(3))
    jit.near_table_above(kt, ot, c, float(floor), FEAS_TOL, low, second, failing)
    return low, second, failing


def pair_margins(keys: SpringKeys, options: SpringOptions, key_idx, option_idx, *, engine: str = "numba",
                 settings: Settings = DEFAULT) -> np.ndarray:
    """(a) for listed pairs: ``out[p, m]`` = margin ``checks()[m]`` of key ``key_idx[p]`` x option
    ``option_idx[p]`` (the rows a caller needs of the product, as :func:`margins` gives the whole product);
    ``engine="numpy"``: the registry path on those pairs (:func:`synth.design.evaluate.spring_values`,
    :func:`~synth.design.evaluate.finish`)."""
    engine = check_engine(engine, settings)
    same_constants(keys, options)
    ki = np.ascontiguousarray(np.asarray(key_idx, dtype=np.int64).reshape(-1))
    oj = np.ascontiguousarray(np.asarray(option_idx, dtype=np.int64).reshape(-1))
    if ki.shape != oj.shape:
        raise InputError(Problem("option_idx", f"{oj.size} options", f"one per key index ({ki.size})"))
    if engine == "numpy":
        x = {k: v[ki] for k, v in keys.raw.items() if k != "fatigue_verified"}
        o = {k: v[oj] for k, v in options.raw.items()}
        v = evaluate.spring_values(o, x, settings)
        g = _group(keys, ki, {name: np.broadcast_to(val, ki.shape) for name, val in v.items()}, settings)
        names = checks()
        return np.stack([g.margins[m] for m in names], axis=-1) if ki.size else np.zeros((0, len(names)))
    jit, kt, ot, c = kernel_tables(keys, options)
    out = np.empty((ki.size, jit.N_MARGINS))
    jit.margins_pairs(kt, ot, c, ki, oj, out)
    return out
