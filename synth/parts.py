"""Catalog data as arrays: every part family and lookup the evaluator needs, loaded once per catalog setting.

:func:`arrays` reads the CSVs of :mod:`synth.catalog` (built-in and user
folders) once per user-folder setting and returns a :class:`Parts` of plain
numpy arrays: strings become integer codes, per-environment and per-fuel
columns become 2-D tables indexed by code. An evaluation never filters a
DataFrame: it gathers by code (``parts.bearing.D_mm[codes]``).

Codes: environments ``ENVIRONMENTS`` (``dry`` 0, ``belt_in_oil`` 1), fuels
``FUELS`` (``gasoline`` 0, ``diesel`` 1).

This module is also the one place for "the next standard size" (bushing
lengths) and for friction coefficients (:func:`mu`).

>>> p = arrays()
>>> str(p.bearing.key[0]), float(p.bearing.D_mm[p.bearing.code("6006")])
('6006', 55.0)
>>> round(mu("pivot_bushing", "belt_in_oil"), 3)
0.055
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from synth import catalog
from synth.cost import book
from synth.errors import CatalogError, Problem
from synth.fingerprint import cached, catalogs_sha256, source_stamp

__all__ = ["ENVIRONMENTS", "FUELS", "Table", "Parts", "arrays", "mu", "env_code", "fuel_code",
           "next_catalog_length_mm"]

ENVIRONMENTS = ("dry", "belt_in_oil")
FUELS = ("gasoline", "diesel")
_ENV_SUFFIX = {"dry": "dry", "belt_in_oil": "bio"}


def env_code(environment) -> np.ndarray:
    """Integer codes of application types (``dry`` 0, ``belt_in_oil`` 1)."""
    return _codes(environment, ENVIRONMENTS, "application_type")


def fuel_code(fuel) -> np.ndarray:
    """Integer codes of engine fuels (``gasoline`` 0, ``diesel`` 1)."""
    return _codes(fuel, FUELS, "engine_fuel")


def _codes(values, choices, name) -> np.ndarray:
    arr = np.atleast_1d(np.asarray(values, dtype=object))
    out = np.empty(arr.shape, dtype=np.int64)
    for i, v in enumerate(arr.ravel()):
        if v not in choices:
            raise CatalogError(Problem(name, v, "one of " + ", ".join(choices)))
        out.flat[i] = choices.index(v)
    return out


@dataclass
class Table:
    """One catalog as arrays: ``key`` (designations) and one array per numeric column."""

    name: str
    key: np.ndarray
    cols: dict = field(default_factory=dict)

    def __getattr__(self, item):
        cols = self.__dict__.get("cols", {})
        if item in cols:
            return cols[item]
        raise AttributeError(item)

    def __len__(self) -> int:
        return len(self.key)

    def code(self, key, field_name: str | None = None) -> int:
        """The code (row position) of designation ``key``; an unknown key lists the valid ones."""
        hit = np.flatnonzero(self.key == str(key).strip())
        if not len(hit):
            raise CatalogError(Problem(field_name or self.name, key, "one of " + ", ".join(map(str, self.key))))
        return int(hit[0])


def _bool(col) -> np.ndarray:
    return np.array([str(x).strip().lower() in ("true", "1", "yes") for x in col], dtype=bool)


def _num(df, col) -> np.ndarray:
    return np.asarray(df[col].astype(float).to_numpy(), dtype=float)


def _table(name: str, df, numeric: tuple, flags: tuple = ("standard",), strings: tuple = ()) -> Table:
    t = Table(name, np.asarray(df[df.columns[0]].astype(str).str.strip().to_numpy(), dtype=object))
    for c in numeric:
        t.cols[c] = _num(df, c)
    for c in flags:
        t.cols[c] = _bool(df[c])
    for c in strings:
        t.cols[c] = np.asarray(df[c].astype(str).str.strip().to_numpy(), dtype=object)
    return t


@dataclass
class Parts:
    """Every catalog the design space and the evaluator read, as arrays (see the module docstring)."""

    bearing: Table
    bearing_max_hubload_n: np.ndarray       # (n_bearings, n_fuels); inf = no upper bound (last Table 1 row)
    table2: dict                            # bearing code -> (working arms, pivot classes, max loading arms), sorted
    bushing: Table                          # suppliers
    bushing_limits: dict                    # name -> (n_suppliers, n_envs): p, pv, pvt max, k_w (NaN = not rated)
    bushing_lengths: list                   # per supplier: sorted catalog lengths [mm]
    damper_pad: Table
    endcap_spacer: Table
    spring_material: Table
    spring_strength: dict                   # grade -> (d_mm, Rm_min_mpa, Rm_max_mpa) sorted by d (every grade of the
                                            # strength table, not only the selectable materials)
    spring_wire: Table
    bolt: Table
    bolt_head: Table                        # format x head type ("M8x1.25 hex"): dw, head size, cost factor
    bolt_class: Table
    washer: Table                           # washers.csv: series (product_standard) x bolt diameter
    tightening: Table                       # tightening_factors.csv: alpha_A range, what sets the preload
    plastic: dict                           # (k_wear, mu) per environment of the standard plastic material
    durability: Table
    cone_ranges: dict                       # parameter -> (min, max)
    cone_clearances: tuple                  # (di_min, di_max, clearance) arrays
    friction: dict                          # interface -> (n_envs,) mu
    #: every part's unit price at the default annual volume (:mod:`synth.cost.book`; the design space's cost
    #: columns are made of it, :mod:`synth.cost.columns`)
    prices: object = None


@functools.lru_cache(maxsize=8)
def _arrays_cached(user_dirs: tuple) -> Parts:
    """The parts of these catalogs, read once per catalog data and synth source (the on-disk cache of
    :func:`synth.fingerprint.cached`)."""
    return cached("parts", [catalogs_sha256(user_dirs), source_stamp()], _read_parts)


def _read_parts() -> Parts:
    load = catalog.load
    bear = load("ball_bearings")
    b = _table("ball_bearings", bear, ("d_mm", "D_mm", "B_mm", "C_n", "C0_n", "ball_count", "ball_diameter_mm"))
    sel = load("bearing_selection")
    hub = np.full((len(b), len(FUELS)), np.nan)
    for _, r in sel.iterrows():
        key = str(r["designation"]).strip()
        if key in set(b.key):
            hub[b.code(key), FUELS.index(str(r["engine_fuel"]).strip())] = float(r["max_hubload_nominal_n"])
    t2 = {}
    piv = load("pivot_classes")
    for i, key in enumerate(b.key):
        rows = piv[piv["bearing"].astype(str).str.strip() == key].sort_values("working_arm_mm")
        t2[i] = tuple(_num(rows, c) for c in ("working_arm_mm", "pivot_class_diameter_mm", "max_loading_arm_mm"))
    bush = load("pivot_bushings")
    bt = _table("pivot_bushings", bush, ("radial_thickness_mm", "sliding_layer_depth_mm", "radial_clearance_mm"),
                strings=("material",))
    limits = {}
    for name, col in (("p_max_mpa", "p_max_{}_mpa"), ("pv_max_mpa_m_per_s", "pv_max_{}_mpa_m_per_s"),
                      ("pvt_max_mpa_m_per_s_h", "pvt_max_{}_mpa_m_per_s_h"), ("k_w_mm3_per_n_m", "k_w_{}_mm3_per_n_m")):
        limits[name] = np.stack([_num(bush, col.format(_ENV_SUFFIX[e])) for e in ENVIRONMENTS], axis=1)
    lengths = [np.sort(np.array([float(x) for x in str(v).split(";") if x.strip()])) for v in bush["lengths_mm"]]
    dp = _table("damper_pads", load("damper_pads"), ("max_axial_damping_nm", "contact_area_mm2", "mean_radius_mm",
                                                     "outer_diameter_mm", "axial_height_mm"))
    es = _table("endcap_spacers", load("endcap_spacers"), ("max_axial_damping_nm", "contact_area_mm2", "mean_radius_mm",
                                                           "axial_height_mm"))
    mat = _table("spring_materials", load("spring_materials"), ("E_mpa", "G_mpa", "density_kg_m3",
                                                               "sigma_y_bend_fraction", "sigma_A0_fraction",
                                                               "sigma_perm_static_fraction"),
                 strings=("wire_sections",))
    strength_df = load("spring_material_strength")
    grade = strength_df["material"].astype(str).str.strip()
    strength = {g: (_num(rows, "d_mm"), _num(rows, "Rm_min_mpa"), _num(rows, "Rm_max_mpa"))
                for g, rows in strength_df.assign(material=grade).sort_values("d_mm").groupby("material", sort=True)}
    for key in mat.key:
        if key not in strength:
            raise CatalogError(Problem("spring_material_strength.csv", key, "tensile strength rows for every material "
                                       "of spring_materials.csv"))
    wires = load("spring_wires")
    w = _table("spring_wires", wires, ("b_mm", "h_mm", "b_tol_mm", "h_tol_mm"), strings=("section",))
    w.cols["round_wire"] = np.array([s == "round" for s in w.section], dtype=bool)
    bolts = load("bolts")
    bo = _table("bolts", bolts, ("d_mm", "pitch_mm", "d2_mm", "d3_mm", "D1_mm", "stress_area_mm2", "pivot_bore_min_mm",
                                 "escalation_rank"))
    heads = load("bolt_heads")
    bh = _table("bolt_heads", heads, ("dw_min_mm", "head_outer_mm", "head_height_mm"),
                strings=("bolt_format", "head_type"))
    bh.cols["bolt_code"] = np.array([bo.code(f, "bolt_heads.bolt_format") for f in bh.bolt_format], dtype=np.int64)
    cls = _table("bolt_property_classes", load("bolt_property_classes"),
                 ("rm_min_mpa", "rp02_min_mpa", "rm_min_d_gt16_mpa", "rp02_min_d_gt16_mpa", "d_max_mm",
                  "escalation_rank", "unit_cost_factor"))
    ws = _table("washers", load("washers"), ("d_mm", "d1_mm", "d2_mm", "h_mm"),
                strings=("product_standard",))
    tf = _table("tightening_factors", load("tightening_factors"), ("alpha_a_min", "alpha_a_max"),
                flags=("standard", "design_option"), strings=("preload_set_by",))
    pw = load("plastic_wear")
    std = pw[pw[pw.columns[0]].astype(str) == "PPA_CF10_AR10_PTFE"].iloc[0]
    plastic = {"k_wear_mm3_per_n_m": np.array([float(std[f"k_wear_{e}_mm3_per_n_m"]) for e in ENVIRONMENTS]),
               "mu": np.array([float(std[f"mu_{e}"]) for e in ENVIRONMENTS])}
    dur = _table("durability_tests", load("durability_tests"), ("theta_peak_to_peak_deg", "frequency_hz",
                                                                "duration_h"), flags=())
    rng = load("cone_spring_ranges")
    cone_ranges = {str(r["parameter"]).strip(): (float(r["min_ratio"]), float(r["max_ratio"])) for _, r in rng.iterrows()}
    clr = load("cone_spring_clearances").sort_values("di_min_mm")
    fr = load("friction_coefficients")
    friction = {}
    for iface in dict.fromkeys(fr["interface"].astype(str).str.strip()):
        rows = fr[fr["interface"].astype(str).str.strip() == iface]
        envs = {str(e).strip(): float(m) for e, m in zip(rows["environment"], rows["mu"])}
        friction[iface] = np.array([envs.get(e, envs.get("any", np.nan)) for e in ENVIRONMENTS])
    p = Parts(b, hub, t2, bt, limits, lengths, dp, es, mat, strength, w, bo, bh, cls, ws, tf, plastic, dur,
              cone_ranges, tuple(_num(clr, c) for c in ("di_min_mm", "di_max_mm", "clearance_mm")), friction)
    p.prices = book.build(p)
    return p


def arrays() -> Parts:
    """The catalogs of the current user-folder setting as :class:`Parts` (cached; do not modify)."""
    return _arrays_cached(tuple(catalog.user_dirs()))


def mu(interface: str, environment) -> float | np.ndarray:
    """Friction coefficient of ``interface`` in ``environment`` (a name, or codes of :func:`env_code`).

    The one friction lookup of synth (``catalogs/friction_coefficients.csv``;
    a row with environment ``any`` serves every environment). An interface or
    environment without a value raises :class:`~synth.errors.CatalogError`.
    """
    table = arrays().friction
    if interface not in table:
        raise CatalogError(Problem("friction interface", interface, "one of " + ", ".join(sorted(table))))
    codes = env_code(environment) if isinstance(environment, str) or np.asarray(environment).dtype == object \
        else np.asarray(environment, dtype=np.int64)
    out = table[interface][codes]
    if np.isnan(out).any():
        raise CatalogError(Problem("application_type", environment,
                                   f"an environment with a friction coefficient for {interface}"))
    return float(out[0]) if isinstance(environment, str) else out


def next_catalog_length_mm(length_mm, lengths_mm: np.ndarray):
    """The shortest catalog length >= ``length_mm`` (the longest one if none is): "round up to the next size".

    >>> float(next_catalog_length_mm(16.0, np.array([10., 12., 15., 18., 20.])))
    18.0
    """
    length = np.asarray(length_mm, dtype=float)
    idx = np.clip(np.searchsorted(lengths_mm, length - 1e-9), 0, len(lengths_mm) - 1)
    return lengths_mm[idx]
