"""Input case of the shrink-fit scene: YAML, JSON or TOML into a validated dataclass.

Format as ``shared/cases/shrink_fit_kia_ceed.yaml``: a ``name``, an
``inputs:`` mapping (or the same keys at top level) and an optional
``model:`` mapping of modelling choices (or the string ``"paper"`` for the
choices that reproduce the paper's tables). Bad input raises
:class:`synth.errors.InputError` with one :class:`~synth.errors.Problem`
per bad field.

Extra keys beyond the paper's case (all optional):

* ``roughness.journal_initial: {Rz: 4.8}`` -- journal roughness before the
  first displacement (the paper's sec. 3.3: Ra 0.8 um, Rz 4.8 um); default:
  the measured journal Rz;
* ``load_torque.camshafts`` (default 1), ``journal_material``,
  ``hub_material`` (keys of ``catalogs/shrink_fit_materials.csv``),
  ``slip_safety`` (default constant ``shrink_fit_slip_safety_min``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

from synth.catalog import constant, row
from synth.errors import CatalogError, InputError, Problem
from synth.io.limits import short
from synth.io.structured import read_document
from synth.shrink_fit.fits import fit_limits
from synth.shrink_fit.roughness import surface

#: realistic bounds of the case's numbers: each keeps every array finite and says why
_E_WHY = ("engineering metals: magnesium alloys about 45 GPa to cemented carbide about 650 GPa; "
          "1e308 would give infinite pressures and margins")
_HB_WHY = ("the Brinell test's range, ISO 6506-1: up to 650 HBW; at least 3.2 HBW, the softest a Brinell test "
           "measures (its lowest force-diameter ratio, 1, with the largest indentation, d = 0.6 D: "
           "0.102 x 2F / (pi D (D - sqrt(D^2 - d^2))) = 3.18)")
_HB_MIN = 3.2
_ISO4288 = ("the classes of ISO 4288:1996 Tables 1-3: Ra from 0.006 to 80 um, Rz from 0.025 to 200 um, RSm from "
            "0.013 to 4 mm (Rp and Rv, the parts of Rz, from 0.0125 um)")
_RA_MAX, _RZ_MAX, _RSM_MAX = 80.0, 200.0, 4000.0
_RA_MIN, _RZ_MIN, _RSM_MIN, _RPV_MIN = 0.006, 0.025, 13.0, 0.0125
_ISO286 = "ten times the largest journal of the catalog's ISO 286-2 fits (50 mm)"
_U_MAX = 2.0
_U_WHY = "a diametral interference of 2 mm is 0.4 % of the largest journal: far beyond yield for any steel"

__all__ = ["Roughness", "LoadTorque", "ModelOptions", "PAPER_MODEL", "ShrinkFitCase", "load_case", "case_from_dict"]


@dataclass(frozen=True)
class Roughness:
    """Roughness of one surface [um]; Sm, Rp, Rv may be None (estimated)."""

    ra_um: float
    rz_um: float
    sm_um: float | None = None
    rp_um: float | None = None
    rv_um: float | None = None


@dataclass(frozen=True)
class LoadTorque:
    """Camshaft friction torque, belt ratio, and any pulley torques the user states."""

    camshaft_friction_torque_max_nm: float | None = None
    gear_ratio: float | None = None
    camshafts: int = 1
    stated_pulley_torques_nm: dict = field(default_factory=dict)


@dataclass(frozen=True)
class ModelOptions:
    """Named modelling choices (defaults: physically consistent; see docs/sections/shrink_fit.md)."""

    smoothing_rule: str = "din7190_2001"      # or "din7190_2017"
    pressure_rule: str = "lame"               # or "paper_eq17"
    adhesion_hardness: str = "softer"         # or "harder" (paper Table 3)
    load_rule: str = "power_balance"          # or "paper"
    rp_rv_from_rz: bool = False               # True: Rp = 0.5 Rz, Rv = 1.2 Rp (paper Table 1)
    friction_model: str = "regime"            # or "elastic", "plastic"


#: the choices that reproduce the paper's Tables 1-4
PAPER_MODEL = ModelOptions(pressure_rule="paper_eq17", adhesion_hardness="harder", load_rule="paper",
                           rp_rv_from_rz=True)

_CHOICES = {
    "smoothing_rule": ("din7190_2001", "din7190_2017"),
    "pressure_rule": ("lame", "paper_eq17"),
    "adhesion_hardness": ("softer", "harder"),
    "load_rule": ("power_balance", "paper"),
    "friction_model": ("regime", "elastic", "plastic"),
}


@dataclass(frozen=True)
class ShrinkFitCase:
    """A validated crankshaft-pulley shrink fit (lengths mm, stresses MPa, roughness um)."""

    name: str
    journal_outer_diameter_mm: float
    journal_inner_diameter_mm: float
    hub_outer_diameter_mm: float
    bore_length_mm: float
    young_modulus_mpa: float
    interference_min_mm: float
    interference_max_mm: float
    assemblies: int
    journal_hardness_hb: float
    hub_hardness_hb: float
    new_hub_bore: Roughness
    worn_hub_bore: Roughness
    journal: Roughness
    journal_initial_rz_um: float
    load: LoadTorque
    fit: str | None = None
    tau0_mpa: float = 1256.0
    beta: float = 0.072
    t_m: float = 0.5
    sm_over_ra: float = 1000.0
    journal_material: str = "38MnVS6"
    hub_material: str = "hub_42HRC"
    journal_yield_mpa: float = 520.0
    hub_yield_mpa: float = 1100.0
    slip_safety: float = 1.5
    model: ModelOptions = ModelOptions()

    def with_model(self, **changes) -> "ShrinkFitCase":
        """A copy with some model options changed (validated)."""
        problems = [Problem(f"model.{k}", v, "one of " + ", ".join(_CHOICES[k]))
                    for k, v in changes.items() if k in _CHOICES and v not in _CHOICES[k]]
        if problems:
            raise InputError(problems)
        return replace(self, model=replace(self.model, **changes))


def _read_file(path: Path) -> dict:
    """The parsed case file, through the input gate (size, UTF-8, YAML aliases, nesting, huge numbers)."""
    data = read_document(path, "INPUT", accepted="an existing YAML, JSON or TOML file")
    if not isinstance(data, dict):
        raise InputError(Problem("INPUT", str(path), "a mapping with an 'inputs:' section"))
    return data


def load_case(path) -> ShrinkFitCase:
    """Read and validate a shrink-fit case from a YAML, JSON or TOML file."""
    path = Path(path)
    data = _read_file(path)
    data.setdefault("name", path.stem)
    return case_from_dict(data)


class _Collector:
    """Reads fields of a mapping, collecting one Problem per bad field."""

    def __init__(self, data: dict, prefix: str = ""):
        self.data, self.prefix, self.problems = data, prefix, []

    def num(self, key, *, default=None, required=True, lo=None, lo_open=False, integer=False, accepted=None,
            hi=None, why=""):
        """The number at ``key`` within ``[lo, hi]`` (``why``: the reason for the bounds, shown on a problem)."""
        name = self.prefix + key
        value = self.data.get(key, default)
        if value is None:
            if required:
                self.problems.append(Problem(name, None, accepted or "a number"))
            return None
        shown = short(value)
        try:
            x = float(value.strip().replace(",", ".")) if isinstance(value, str) else float(value)
            if isinstance(value, bool) or not math.isfinite(x):
                raise ValueError
        except (TypeError, ValueError, OverflowError):
            self.problems.append(Problem(name, shown, accepted or "a finite number"))
            return None
        if integer and x != int(x):
            self.problems.append(Problem(name, shown, accepted or "a whole number"))
            return None
        if lo is not None and (x <= lo if lo_open else x < lo):
            self.problems.append(Problem(name, shown, (accepted or f"a number {'>' if lo_open else '>='} {lo:g}")
                                         + (f" ({why})" if why and not accepted else "")))
            return None
        if hi is not None and x > hi:
            self.problems.append(Problem(name, shown, f"a number <= {hi:g}" + (f" ({why})" if why else "")))
            return None
        return int(x) if integer else x


def _roughness(raw, name, problems) -> Roughness | None:
    if not isinstance(raw, dict):
        problems.append(Problem(name, raw, "a mapping with Ra and Rz (and optionally Sm, Rp, Rv) in um"))
        return None
    c = _Collector({str(k).lower(): v for k, v in raw.items()}, name + ".")
    ra = c.num("ra", lo=_RA_MIN, accepted=f"Ra in um, >= {_RA_MIN:g}", hi=_RA_MAX, why=_ISO4288)
    rz = c.num("rz", lo=_RZ_MIN, accepted=f"Rz in um, >= {_RZ_MIN:g}", hi=_RZ_MAX, why=_ISO4288)
    sm = c.num("sm", required=False, lo=_RSM_MIN, accepted=f"Sm in um, >= {_RSM_MIN:g}", hi=_RSM_MAX, why=_ISO4288)
    rp = c.num("rp", required=False, lo=_RPV_MIN, accepted=f"Rp in um, >= {_RPV_MIN:g}", hi=_RZ_MAX, why=_ISO4288)
    rv = c.num("rv", required=False, lo=_RPV_MIN, accepted=f"Rv in um, >= {_RPV_MIN:g}", hi=_RZ_MAX, why=_ISO4288)
    unknown = set(c.data) - {"ra", "rz", "sm", "rp", "rv"}
    problems.extend(c.problems)
    if unknown:
        problems.append(Problem(name, sorted(unknown, key=str), "only the keys Ra, Rz, Sm, Rp, Rv"))
    if ra is None or rz is None:
        return None
    return Roughness(ra, rz, sm, rp, rv)


def _model(raw, problems) -> ModelOptions:
    if raw is None:
        return ModelOptions()
    if raw == "paper":
        return PAPER_MODEL
    if not isinstance(raw, dict):
        problems.append(Problem("model", raw, "'paper' or a mapping of " + ", ".join(f.name for f in fields(ModelOptions))))
        return ModelOptions()
    base = PAPER_MODEL if raw.get("preset") == "paper" else ModelOptions()
    changes = {}
    for k, v in raw.items():
        if k == "preset":
            if v not in ("paper", "default"):
                problems.append(Problem("model.preset", v, "'paper' or 'default'"))
        elif k in _CHOICES:
            if v not in _CHOICES[k]:
                problems.append(Problem(f"model.{k}", v, "one of " + ", ".join(_CHOICES[k])))
            else:
                changes[k] = v
        elif k == "rp_rv_from_rz":
            if not isinstance(v, bool):
                problems.append(Problem("model.rp_rv_from_rz", v, "true or false"))
            else:
                changes[k] = v
        else:
            problems.append(Problem(f"model.{k}", v, "one of the keys preset, " + ", ".join(f.name for f in fields(ModelOptions))))
    return replace(base, **changes)


_INPUT_KEYS = {
    "journal_outer_diameter_mm", "journal_inner_diameter_mm", "hub_outer_diameter_mm", "bore_length_mm",
    "young_modulus_mpa", "fit", "interference_min_mm", "interference_max_mm", "assemblies",
    "journal_hardness_hb", "hub_hardness_hb", "tau0_mpa", "beta", "t_m", "sm_over_ra", "roughness",
    "load_torque", "journal_material", "hub_material", "slip_safety", "model",
}


def case_from_dict(data: dict) -> ShrinkFitCase:
    """Validate a mapping (the parsed file) into a :class:`ShrinkFitCase`.

    >>> try:
    ...     case_from_dict({"inputs": {"journal_outer_diameter_mm": 30}})
    ... except InputError as exc:
    ...     print(len(exc.problems), exc.problems[0])
    10 hub_outer_diameter_mm: missing; expected a number
    """
    inputs = data.get("inputs", data)
    if not isinstance(inputs, dict):
        raise InputError(Problem("inputs", inputs, "a mapping of the case's inputs"))
    problems: list[Problem] = []
    unknown = set(inputs) - _INPUT_KEYS - ({"name", "inputs", "model", "thesis_tool", "real_tensioner"} if inputs is data else set())
    problems.extend(Problem(k, inputs[k], "one of the keys " + ", ".join(sorted(_INPUT_KEYS))) for k in sorted(unknown, key=str))
    c = _Collector(inputs)
    d = c.num("journal_outer_diameter_mm", lo=1, hi=500, why=_ISO286 + "; ISO 286-2 tabulates from 1 mm")
    dww = c.num("journal_inner_diameter_mm", default=0.0, lo=0, hi=500, why=_ISO286)
    dzo = c.num("hub_outer_diameter_mm", lo=1, hi=2000, why="four times the largest journal; at least ISO 286's 1 mm")
    length = c.num("bore_length_mm", lo=0.1, hi=1000, why="twice the largest journal diameter; at least 0.1 mm, "
                                                           "a manufacturability floor (a hub has a length)")
    e = c.num("young_modulus_mpa", default=constant("shrink_fit_young_modulus_steel_mpa"), lo=40_000, hi=700_000,
              accepted=f"a number in [40000, 700000] MPa ({_E_WHY})", why=_E_WHY)
    n = c.num("assemblies", default=0, lo=0, integer=True, hi=200,
              accepted="a whole number in [0, 200] (sliding assemblies/disassemblies i of eq. 19; twice the "
                       "largest --reassemblies)")
    hb_s = c.num("journal_hardness_hb", lo=_HB_MIN, hi=650, why=_HB_WHY)
    hb_h = c.num("hub_hardness_hb", lo=_HB_MIN, hi=650, why=_HB_WHY)
    tau0 = c.num("tau0_mpa", default=constant("shrink_fit_tau0_mpa"), lo=0, hi=10_000,
                 why="a shear strength of the adhesive bonds above that of any steel")
    beta = c.num("beta", default=constant("shrink_fit_beta"), lo=0, hi=1, why="a fraction (eq. 2)")
    t_m = c.num("t_m", default=constant("shrink_fit_t_m"), lo=0, lo_open=True, hi=1,
                why="a relative bearing-area level (eq. 4-6)")
    sm_ra = c.num("sm_over_ra", default=constant("shrink_fit_sm_over_ra"), lo=0, lo_open=True, hi=1e4,
                  why="ten times the case's default ratio")
    safety = c.num("slip_safety", default=constant("shrink_fit_slip_safety_min"), lo=0, lo_open=True, hi=20,
                   why="a safety factor")
    neg = "a non-negative diametral interference in mm (a shrink fit needs the journal larger than the bore)"
    u_min = c.num("interference_min_mm", required=False, lo=0, accepted=neg, hi=_U_MAX, why=_U_WHY)
    u_max = c.num("interference_max_mm", required=False, lo=0, lo_open=True, accepted=neg.replace("non-negative", "positive"),
                  hi=_U_MAX, why=_U_WHY)
    problems.extend(c.problems)

    if d is not None and dww is not None and dww >= d:
        problems.append(Problem("journal_inner_diameter_mm", dww, f"0 <= value < journal_outer_diameter_mm ({d:g})"))
    if d is not None and dzo is not None and dzo <= d:
        problems.append(Problem("hub_outer_diameter_mm", dzo, f"a value > journal_outer_diameter_mm ({d:g})"))

    fit = inputs.get("fit")
    if fit is not None:
        try:
            lim = fit_limits(fit)
        except CatalogError as exc:
            problems.extend(exc.problems)
        else:
            if d is not None and abs(lim["diameter_mm"] - d) > 1e-9:
                problems.append(Problem("fit", fit, f"a fit of the journal diameter {d:g} mm"))
            for key, val in (("interference_min_mm", u_min), ("interference_max_mm", u_max)):
                if val is not None and abs(val - lim[key]) > 5e-4:
                    problems.append(Problem(key, val, f"{lim[key]:g} as fit {fit} gives (or omit the fit)"))
            if lim["interference_min_mm"] < 0 and u_min is None:
                problems.append(Problem("fit", fit, f"an interference fit (its minimum interference is "
                                                    f"{lim['interference_min_mm']:g} mm: the joint can be loose)"))
            u_min = lim["interference_min_mm"] if u_min is None else u_min
            u_max = lim["interference_max_mm"] if u_max is None else u_max
    if u_min is None and u_max is None and fit is None:
        problems.append(Problem("interference_min_mm", None, "interference_min_mm and interference_max_mm, or a fit such as '30H7/u6'"))
    elif u_min is not None and u_max is not None and u_min > u_max:
        problems.append(Problem("interference_min_mm", u_min, f"a value <= interference_max_mm ({u_max:g})"))

    rough = inputs.get("roughness")
    surfaces = {}
    if not isinstance(rough, dict):
        problems.append(Problem("roughness", rough, "a mapping with new_hub_bore, worn_hub_bore, journal"))
        rough = {}
    for key in ("new_hub_bore", "worn_hub_bore", "journal"):
        surfaces[key] = _roughness(rough.get(key), f"roughness.{key}", problems)
    extra = set(rough) - {"new_hub_bore", "worn_hub_bore", "journal", "journal_initial"}
    if extra:
        problems.append(Problem("roughness", sorted(extra, key=str), "keys new_hub_bore, worn_hub_bore, journal, journal_initial"))
    rz0 = surfaces["journal"].rz_um if surfaces["journal"] else None
    if "journal_initial" in rough:
        ji = rough["journal_initial"]
        cj = _Collector({str(k).lower(): v for k, v in (ji.items() if isinstance(ji, dict) else {}.items())},
                        "roughness.journal_initial.")
        rz0 = cj.num("rz", lo=_RZ_MIN, accepted=f"Rz in um, >= {_RZ_MIN:g}", hi=_RZ_MAX, why=_ISO4288)
        problems.extend(cj.problems)

    model = _model(data.get("model", inputs.get("model")), problems)

    lt = inputs.get("load_torque") or {}
    if not isinstance(lt, dict):
        problems.append(Problem("load_torque", lt, "a mapping"))
        lt = {}
    cl = _Collector(lt, "load_torque.")
    mc = cl.num("camshaft_friction_torque_max_nm", required=False, lo=0, hi=5000,
                why="fifty times the paper's 96 Nm pulley torque")
    u = cl.num("gear_ratio", required=False, lo=0.05, hi=20,
               why="a belt drive ratio (the paper's is 2): from 1:20 to 20:1, pulley diameters within twenty times")
    ncam = cl.num("camshafts", default=1, lo=1, integer=True, hi=8, why="camshafts driven by one belt")
    stated = {}
    for k, v in lt.items():
        if k.startswith("pulley_torque") and k.endswith("_nm"):
            stated[k] = cl.num(k, lo=0, hi=5000, why="fifty times the paper's 96 Nm pulley torque")
        elif k not in ("camshaft_friction_torque_max_nm", "gear_ratio", "camshafts"):
            cl.problems.append(Problem(f"load_torque.{k}", v, "camshaft_friction_torque_max_nm, gear_ratio, camshafts, pulley_torque_*_nm"))
    problems.extend(cl.problems)
    if (mc is None) != (u is None):
        problems.append(Problem("load_torque", lt, "both camshaft_friction_torque_max_nm and gear_ratio, or neither"))
    if mc is None and not stated:
        problems.append(Problem("load_torque", lt or None, "camshaft_friction_torque_max_nm with gear_ratio, or pulley_torque_*_nm"))

    mats = {}
    for key, default in (("journal_material", "38MnVS6"), ("hub_material", "hub_42HRC")):
        name = str(inputs.get(key, default))
        try:
            mats[key] = (name, float(row("shrink_fit_materials", name, key)["yield_strength_mpa"]))
        except CatalogError as exc:
            problems.extend(exc.problems)
            mats[key] = (name, float("nan"))

    # surfaces the roughness formulas cannot describe (eq. 4-6 domains)
    if not problems:
        for key, s in surfaces.items():
            der = surface(s.ra_um, s.rz_um, s.sm_um, s.rp_um, s.rv_um, t_m, model.rp_rv_from_rz, sm_ra)
            if not (float(der["v"]) > 0 and math.isfinite(float(der["asperity_radius_um"]))):
                problems.append(Problem(f"roughness.{key}", s, f"a surface with Ra < Rp < 5.5 Ra "
                                        f"(here Rp = {float(der['rp_um']):.3g} um; eq. 4 and 6 need it)"))
    if problems:
        raise InputError(problems)
    return ShrinkFitCase(
        name=str(data.get("name", "shrink-fit")), journal_outer_diameter_mm=d, journal_inner_diameter_mm=dww,
        hub_outer_diameter_mm=dzo, bore_length_mm=length, young_modulus_mpa=e,
        interference_min_mm=u_min, interference_max_mm=u_max, assemblies=n,
        journal_hardness_hb=hb_s, hub_hardness_hb=hb_h, new_hub_bore=surfaces["new_hub_bore"],
        worn_hub_bore=surfaces["worn_hub_bore"], journal=surfaces["journal"], journal_initial_rz_um=rz0,
        load=LoadTorque(mc, u, ncam, stated), fit=None if fit is None else str(fit), tau0_mpa=tau0, beta=beta,
        t_m=t_m, sm_over_ra=sm_ra, journal_material=mats["journal_material"][0],
        hub_material=mats["hub_material"][0], journal_yield_mpa=mats["journal_material"][1],
        hub_yield_mpa=mats["hub_material"][1], slip_safety=safety, model=model)
