"""The tolerance model: what scatters in production, by how much, in which distribution, and why.

Declared once, as data: ``catalogs/tolerances.csv`` (one row per quantity,
user-overridable like every catalog: ``synth --catalogs DIR``). A row gives
the distribution ``kind``, the ``band`` (half-width, in ``unit``: ``mm``,
``MPa`` or ``%`` of the nominal value) or where the band comes from
(``band_from``: a catalog column of the chosen part, a named constant, an
input field of the application, a standard's table), the ``source`` and a
``note`` saying why this distribution.

* ``normal``: the band is +/-3 standard deviations (a capable, centred
  process: Cp = 1 on the tolerance, the convention of statistical
  tolerancing);
* ``uniform``: every value in the band equally likely (a range with no
  distribution given: a standard's strength range, a friction range, the
  acceptance window of a force tolerance).

What each quantity perturbs is declared once in code (:class:`Quantity`,
:data:`DECLARED`): the evaluator's input it changes and how, the worst-case
tolerance of the nominal model it replaces, and what the design must have
for it to apply (a quantity absent from the catalog keeps the nominal
model's treatment); a new quantity is one declaration (:func:`declare`) and
one catalog row. :func:`resolve` turns the rows into the :class:`Scatter`
of one design of one application: the quantities in play (a zero band or a
part the design does not have drops them) with their deviation bounds.

>>> t = tolerances()
>>> t["spring_wire_width"].kind, t["bolt_preload"].kind, t["bolt_preload"].band_from
('normal', 'uniform', 'bolt_tightening.alpha_a_max')
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem

__all__ = ["Quantity", "DECLARED", "HOWS", "QUANTITIES", "QUANTITY_UNITS", "UNITS", "KINDS", "Tolerance", "Scatter",
           "tolerances", "resolve", "declare", "withdraw"]

KINDS = ("normal", "uniform")

@dataclass(frozen=True)
class Quantity:
    """What one tolerance quantity perturbs, declared once (its band, distribution and source are its row of
    ``catalogs/tolerances.csv``); :func:`synth.robust.sampling.perturb` reads the declarations.

    ``into`` is where the sampled deviation ``x`` enters: ``"field"`` an application input field, ``"derived"`` a
    value derived from the inputs (``Applications.derived``), a design table (``"core"``, ``"bushing"``,
    ``"axial"``, ``"spring"``, ``"bolt"``: a column of the design's attributes), ``"cone"`` a column of the made
    cone spring (a design with a sized one) or ``"gap"`` the cone spring's gap stack (its deviations summed with
    the sign of ``how``); ``target`` names the field, value or column(s). ``how``: ``"add"`` nominal + x,
    ``"set"`` x, ``"negate"`` -x, ``"relative"`` nominal x (1 + x/100) (``by``: the nominal is the value
    ``"group.key"`` of the design's nominal evaluation instead of the target's own), ``"factor"`` 1 + x/100,
    ``"scale_by"`` each target column times 1 + x / (column ``by``). ``zero``: the worst-case tolerances of the
    nominal model the sample replaces, set to 0 (``"field:NAME"`` or ``"TABLE:COLUMN"``). ``needs``: the key of the
    design's context (:func:`synth.robust.sampling.context`) without which the quantity is dropped, ``why`` says so.
    ``always``: applied at a zero deviation when the quantity is not in play (the made spring's torque).
    """

    name: str
    enters: str
    unit: str
    into: str
    target: str | tuple
    how: str = "add"
    by: str = ""
    zero: tuple = ()
    needs: str = ""
    why: str = ""
    always: bool = False

    def __post_init__(self):
        if self.how not in HOWS:
            raise ValueError(f"tolerance quantity {self.name}: how {self.how!r}, one of {', '.join(HOWS)}")
        if self.unit not in UNITS:
            raise ValueError(f"tolerance quantity {self.name}: unit {self.unit!r}, one of {', '.join(UNITS)}")


#: the ways a deviation enters (:class:`Quantity`)
HOWS = ("add", "set", "negate", "relative", "factor", "scale_by")
#: the unit each quantity's band is given in, and the largest band synth accepts (a larger one makes the quantity
#: zero or negative, or its samples non-finite): unit -> (largest half-width, why)
UNITS = {"mm": (10.0, "a larger one exceeds the tensioner's dimensions"),
         "MPa": (1000.0, "a larger one exceeds the strength of the spring wire"),
         "%": (100.0, "a larger one makes the quantity zero or negative")}

_NO_CONE = "no cone spring in the design"

#: the tolerance quantities synth knows, in order (:func:`declare`, :func:`withdraw`)
DECLARED = {q.name: q for q in (
    Quantity("spring_wire_width", "main spring wire width b (spring option b_mm; b_tol_mm of eq. (89)-(93) set to 0)",
             "mm", "spring", "b_mm", zero=("spring:b_tol_mm",)),
    Quantity("spring_wire_height", "main spring wire radial side h (spring option h_mm; h_tol_mm of eq. (83)-(88) set "
             "to 0)", "mm", "spring", "h_mm", zero=("spring:h_tol_mm",)),
    Quantity("spring_coil_diameter", "main spring mean body diameter (spring option; mbd_tol of eq. (83)-(88) set to "
             "0)", "mm", "spring", "main_spring_mean_body_diameter_mm", zero=("spring:mbd_tol_mm",)),
    Quantity("spring_tensile_strength", "main spring wire tensile strength Rm (and sigma_y, sigma_A0, the static limit "
             "with it)", "MPa", "spring", ("Rm_mpa", "sigma_y_mpa", "sigma_A0_mpa", "sigma_perm_static_mpa"),
             how="scale_by", by="Rm_mpa"),
    Quantity("spring_torque", "the made spring's torque at the nominal position (eq. (66)'s toleranced quantity): the "
             "tensioner's damping, calculated torque and hubload follow by eq. (12)-(13); the one-sided worst case of "
             "eq. (66) set to 0", "%", "derived", "spring_torque_made_nm", how="relative",
             by="core.spring_torque_nominal_nm", zero=("field:spring_torque_tolerance_pct",), always=True),
    Quantity("spring_housing_outer_diameter", "spring housing bore (the limit of eq. (82))", "mm", "spring",
             "housing_outer_tol_mm", how="negate"),  # the limit D_h - tol of eq. (82) becomes D_h + deviation
    Quantity("spring_housing_inner_diameter", "spring support diameter (the limit of eq. (86))", "mm", "spring",
             "housing_inner_tol_mm", how="set"),  # the limit D_s + tol of eq. (86) becomes D_s + deviation
    Quantity("pivot_diameter", "pivot diameter (radial damping lever, bushing pressure)", "mm", "core",
             "pivot_diameter_mm"),
    Quantity("working_arm", "working arm (eccentricity): the lever of eq. (7) and (12)-(13), the Table 2 check", "mm",
             "field", "working_arm_mm"),
    Quantity("belt_offset", "the belt plane's offset in the tilting lever of eq. (95) (the sample instead of the "
             "worst-case increment; the design's dimensions keep the nominal belt plane)", "mm", "field",
             "middle_plane_belt_height_increment_worst_mm", how="set"),
    Quantity("pulley_diameter", "pulley diameter (lock-up pin checks, eq. (22)-(25))", "mm", "field",
             "pulley_diameter_mm"),
    Quantity("pivot_bushing_friction", "pivot bushing friction coefficient (radial damping, eq. (10))", "%", "derived",
             "mu_pivot_bushing", how="relative"),
    Quantity("plastic_friction", "plastic elements' friction coefficient (axial damping, eq. (9))", "%", "derived",
             "mu_plastic", how="relative", needs="cone", why="no axial damping group"),
    Quantity("crankcase_friction", "pivot base-crankcase friction (sliding safety factor, eq. (99))", "%", "derived",
             "mu_crankcase", how="relative"),
    Quantity("bolt_preload", "the made joint's assembly preload, within its tightening method's window "
             "[F_M,min, F_M,max] (VDI 2230-1: alpha_A = F_M,max/F_M,min)", "%", "derived", "bolt_clamp_force_n",
             how="relative", by="bolt.bolt_axial_force_n", needs="bolt", why="no fixation data"),
    Quantity("stack_pivot", "cone spring gap: pivot height (Table 6)", "mm", "gap", "", needs="cone", why=_NO_CONE),
    Quantity("stack_endcap_spacer", "cone spring gap: endcap spacer height (Table 6)", "mm", "gap", "", how="negate",
             needs="cone", why=_NO_CONE),
    Quantity("stack_arm", "cone spring gap: arm hub height (Table 6)", "mm", "gap", "", how="negate", needs="cone",
             why=_NO_CONE),
    Quantity("stack_damper_pad", "cone spring gap: damper pad height (Table 6)", "mm", "gap", "", how="negate",
             needs="cone", why=_NO_CONE),
    Quantity("cone_spring_force", "the made cone spring's force at its deflection (DIN EN 16983 force tolerance)", "%",
             "cone", "force_factor", how="factor", needs="cone", why=_NO_CONE),
)}

#: quantity -> what it perturbs in the evaluator, in words (of :data:`DECLARED`)
QUANTITIES = {q.name: q.enters for q in DECLARED.values()}
#: each quantity's unit (its band's): a row giving another unit is refused (a band of 0.05 in mm and in % differ)
QUANTITY_UNITS = {q.name: q.unit for q in DECLARED.values()}


def declare(q: Quantity) -> Quantity:
    """Add tolerance quantity ``q`` (after the declared ones; a name declared already is an error): a row of the
    tolerance catalog may then name it. :func:`withdraw` undoes it."""
    if q.name in DECLARED:
        raise ValueError(f"tolerance quantity {q.name} is declared already")
    DECLARED[q.name], QUANTITIES[q.name], QUANTITY_UNITS[q.name] = q, q.enters, q.unit
    return q


def withdraw(name: str) -> None:
    """Remove the tolerance quantity ``name`` that :func:`declare` added."""
    del DECLARED[name], QUANTITIES[name], QUANTITY_UNITS[name]


@dataclass(frozen=True)
class Tolerance:
    """One row of ``catalogs/tolerances.csv``."""

    quantity: str
    kind: str
    band: float | None
    unit: str
    band_from: str
    source: str
    note: str
    #: a factor on the band (1: the catalog's; the robust synthesis's search for the band that would allow a design)
    scale: float = 1.0


def tolerances() -> dict:
    """``{quantity: Tolerance}`` of the tolerance catalog (built-in merged with the user's folders), checked: a
    quantity synth does not know, a kind other than normal/uniform, a unit other than the quantity's
    (:data:`QUANTITY_UNITS`), a row with both a ``band`` and a ``band_from`` (or neither), or a band that is not a
    finite number from 0 to the unit's largest (:data:`UNITS`) is an error naming the file, row, column, value and
    what is accepted."""
    df = catalog.load("tolerances")
    out, problems = {}, []
    for i, r in df.iterrows():
        q = str(r["quantity"]).strip()
        where = f"catalog tolerances.csv, row {q}"
        if q not in QUANTITIES:
            problems.append(Problem(f"{where}, column quantity", q, "one of " + ", ".join(QUANTITIES)))
            continue
        kind = str(r["kind"]).strip().lower()
        if kind not in KINDS:
            problems.append(Problem(f"{where}, column kind", r["kind"], "normal (band = +/-3 sigma) or uniform"))
        unit = str(r["unit"]).strip()
        if unit != QUANTITY_UNITS[q]:
            problems.append(Problem(f"{where}, column unit", r["unit"], f"{QUANTITY_UNITS[q]} (the unit of {q}'s band)"))
            unit = QUANTITY_UNITS[q]
        src = "" if _blank(r["band_from"]) else str(r["band_from"]).strip()
        band = None
        if src and not _blank(r["band"]):
            problems.append(Problem(f"{where}, columns band and band_from", f"{r['band']} and {src}",
                                    "either a band or a band_from, not both (which one would hold is ambiguous)"))
        elif not src:
            top, why = UNITS[unit]
            try:
                band = float(r["band"])
            except (TypeError, ValueError):
                band = float("nan")
            if not (math.isfinite(band) and 0 <= band < top):
                problems.append(Problem(f"{where}, column band", r["band"],
                                        f"a half-width from 0 to below {top:g} {unit} ({why}), or a band_from"))
        out[q] = Tolerance(q, kind, band, unit, src, str(r["source"]), str(r.get("note", "")))
    if problems:
        raise InputError(problems)
    return out


def _blank(v) -> bool:
    return v is None or (isinstance(v, float) and math.isnan(v)) or str(v).strip() == ""


@dataclass
class Scatter:
    """The tolerance model of one design of one application: per quantity in play, its distribution and its
    deviation bounds ``[lo, hi]`` (in ``unit``; normal: ``lo = -hi`` = 3 sigma)."""

    names: tuple
    columns: np.ndarray   # (d,) each quantity's position in the catalog (its column of a shared sample)
    kind: np.ndarray      # (d,) 0 normal, 1 uniform
    lo: np.ndarray        # (d,) lower deviation bound
    hi: np.ndarray        # (d,) upper deviation bound
    unit: tuple
    rows: list = field(default_factory=list)   # one dict per quantity: name, kind, band, unit, source, note
    dropped: list = field(default_factory=list)  # (quantity, why) not in play for this design
    width: int = 0                               # quantities in the catalog (columns of a shared sample)

    def __len__(self) -> int:
        return len(self.names)

    def deviations(self, u: np.ndarray) -> np.ndarray:
        """``(N, d)`` deviations of standard-normal points ``u`` (the isoprobabilistic transform: normal
        ``centre + (hi - lo)/6 u``, uniform ``lo + (hi - lo) Phi(u)``).

        >>> s = Scatter(("a", "b"), np.array([0, 1]), np.array([0, 1]), np.array([-0.3, 0.0]), np.array([0.3, 2.0]),
        ...             ("mm", "MPa"))
        >>> s.deviations(np.array([[3.0, 0.0]])).round(6).tolist()
        [[0.3, 1.0]]
        """
        from scipy.special import ndtr
        u = np.asarray(u, dtype=float)
        centre, half = (self.lo + self.hi) / 2.0, (self.hi - self.lo) / 2.0
        normal = centre + half / 3.0 * u
        uniform = self.lo + (self.hi - self.lo) * ndtr(u)
        return np.where(self.kind[None, :] == 0, normal, uniform)

    def centre(self) -> np.ndarray:
        """``(d,)`` the deviations at the centre of every band (the median of every distribution)."""
        return (self.lo + self.hi) / 2.0

    def sigma(self) -> np.ndarray:
        """``(d,)`` standard deviation of each quantity (normal: band/3; uniform: range/sqrt(12))."""
        return np.where(self.kind == 0, (self.hi - self.lo) / 6.0, (self.hi - self.lo) / math.sqrt(12.0))


@functools.lru_cache(maxsize=64)
def _catalog_value(name: str, key: str, column: str, field: str, _dirs: tuple) -> float:
    """One number of a catalog row (kept per catalog setting: a bulk resolves thousands of designs)."""
    return float(catalog.row(name, key, field=field)[column])


@functools.lru_cache(maxsize=8)
def _it_grades(_dirs: tuple) -> tuple:
    """``(over_mm, up_to_mm, {ITn_um: values})`` of ISO 286-1's standard tolerance grades (per catalog setting)."""
    it = catalog.load("iso286_it_grades")
    return (it["over_mm"].to_numpy(float), it["up_to_mm"].to_numpy(float),
            {c: it[c].to_numpy(float) for c in it.columns if c.startswith("IT")})


def _band_from(spec: str, ctx: dict, tol: Tolerance):
    """``(lo, hi)`` of a ``band_from`` reference for the design of ``ctx``, or a string saying why none."""
    kind, _, rest = spec.partition(".")
    if kind == "constants":
        v = catalog.constant(rest)
        return -v, v
    if kind == "input":
        v = ctx["field"](rest)
        return (-v, v) if np.isfinite(v) else f"{rest} not given"
    if kind == "spring_wires":
        v = float(ctx["spring"][rest])
        return -v, v
    if kind == "spring_material_strength":
        return 0.0, ctx["rm_max"] - ctx["rm_min"]
    if kind in ("tightening_factors", "stackup_tolerances"):
        key, _, column = rest.partition(".")
        v = _catalog_value(kind, key, column, f"tolerances.csv {tol.quantity} band_from", tuple(catalog.user_dirs()))
        return -v, v
    if kind == "iso286_it_grades":
        over, up_to, table = _it_grades(tuple(catalog.user_dirs()))
        if rest not in table:
            raise InputError(Problem(f"catalog tolerances.csv, row {tol.quantity}, column band_from", spec,
                                     "iso286_it_grades." + ", iso286_it_grades.".join(table)))
        dia = ctx["pivot_diameter_mm"]
        hit = np.flatnonzero((over < dia) & (dia <= up_to))
        if not len(hit):
            return f"{rest} not tabulated for {dia:g} mm (ISO 286-1 rows {over.min():g} to {up_to.max():g} mm)"
        v = float(table[rest][hit[0]]) / 1000.0 / 2.0
        return -v, v
    if kind == "bolt_tightening":  # the design's own tightening method: its window about the mean, +/- s
        from synth.model.vdi2230 import preload_scatter
        alpha = ctx.get("tightening_alpha_a", float("nan"))
        if not np.isfinite(alpha):
            return "no tightening method"
        v = 100.0 * float(preload_scatter(alpha))
        return -v, v
    if kind == "disc_spring_force_tolerances":
        plus, minus = ctx["cone_force_tolerance"]
        if not (np.isfinite(plus) and np.isfinite(minus)):
            return "the cone spring's thickness is beyond the DIN EN 16983 groups"
        return -100.0 * minus, 100.0 * plus
    raise InputError(Problem(f"catalog tolerances.csv, row {tol.quantity}, column band_from", spec,
                             "constants.NAME, input.FIELD, spring_wires.COLUMN, spring_material_strength, "
                             "tightening_factors.METHOD.COLUMN, stackup_tolerances.COMPONENT.COLUMN, "
                             "iso286_it_grades.ITn_um, disc_spring_force_tolerances or bolt_tightening.alpha_a_max"))


def resolve(ctx: dict, table: dict | None = None) -> Scatter:
    """The :class:`Scatter` of one design: ``ctx`` describes it (see :func:`synth.robust.sampling.base_of`):
    ``field(name)`` (an application input, NaN where not given), ``spring`` (its spring option row),
    ``rm_min``/``rm_max``, ``pivot_diameter_mm``, ``cone`` (a sized cone spring), ``cone_force_tolerance``
    (its DIN EN 16983 fractions), ``bolt`` (the thesis bolt method with fixation data)."""
    table = tolerances() if table is None else table
    names, cols, kinds, los, his, units, rows, dropped = [], [], [], [], [], [], [], []
    for col, (q, tol) in enumerate(table.items()):
        need = DECLARED[q]
        if need.needs and not ctx[need.needs]:
            dropped.append((q, need.why))
            continue
        if tol.band_from:
            b = _band_from(tol.band_from, ctx, tol)
            if isinstance(b, str):
                dropped.append((q, b))
                continue
            lo, hi = b
        else:
            lo, hi = -float(tol.band), float(tol.band)
        lo, hi = lo * tol.scale, hi * tol.scale
        if not (hi > lo):
            dropped.append((q, "zero band"))
            continue
        names.append(q)
        cols.append(col)
        kinds.append(0 if tol.kind == "normal" else 1)
        los.append(lo)
        his.append(hi)
        units.append(tol.unit)
        rows.append({"quantity": q, "kind": tol.kind, "lo": lo, "hi": hi, "unit": tol.unit, "source": tol.source,
                     "note": tol.note, "enters": QUANTITIES[q]})
    return Scatter(tuple(names), np.array(cols, dtype=np.int64), np.array(kinds, dtype=np.int8),
                   np.array(los, dtype=float), np.array(his, dtype=float), tuple(units), rows, dropped, len(table))
