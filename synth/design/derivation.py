"""Each check's derivation on request: the margin with its numbers, and how the value and the limit were computed.

Built from what synth already declares, never from a second copy of an equation:

* the **registry** (:mod:`synth.design.constraints`): the check's value, limit and scale keys, its sense, equation
  reference and unit, and the margin rule (:func:`~synth.design.constraints.normalised_margin`), shown with the
  numbers substituted;
* the **physics functions** of :mod:`synth.model`, recorded while the one evaluator evaluates the design
  (:func:`synth.design.verify.evaluate_design` with them wrapped: :func:`synth.design.trace.traced`): each call's named inputs with their values
  and its outputs; a value is explained by the innermost call that produced it, its equation by that function's
  docstring (its summary and ``.. math::`` lines, with the equation numbers of the thesis or standard);
* the **evaluator's own lines** (:mod:`synth.design.evaluate`), read from its source for a value a group computes
  without a physics call (``v["damping_upper_nm"] = f["damping_target_nm"] + f["damping_tolerance_nm"]``);
* the **sources**: a design input (its schema label, given or a documented default), a named constant (its catalog
  file, value, unit and ``source`` column), a part's catalog row (its file, designation and ``source``).

:func:`derive` returns a :class:`Derivation` (plain data: :meth:`Derivation.as_dict` is what the web page reads);
the terminal (``synth design --explain CHECK``), the report's appendix and :func:`synth.derive` present it.

>>> from synth.scenes.demo import default_input
>>> parts = {"ball_bearing": "6006", "pivot_class_diameter_mm": 17.0, "pivot_bushing_supplier": "B",
...     "damper_pad_class": "none", "pivot_bushing_length_mm": 15.0, "endcap_spacer_class": "none",
...     "cone_spring_aspect_ratio": 0.0, "cone_spring_deflection_ratio": 0.0, "cone_spring_external_diameter_mm": 0.0,
...     "cone_spring_internal_diameter_mm": 0.0,
...     "main_spring_material": "VDSiCrV", "main_spring_wire": "F2.00x2.00", "main_spring_mean_body_diameter_mm": 43.0,
...     "bolt_format": "M8x1.25", "bolt_head_type": "hex", "bolt_property_class": "8.8"}
>>> dv = derive(default_input(), parts, "self_locking")
>>> dv.value.key, round(dv.value.value, 4), dv.value.step.function
('lever_ratio', 0.2239, 'synth.model.damping.lever_ratio')
>>> [q.key for q in dv.value.step.inputs][:2], dv.value.step.inputs[1].origin
(['pivot_diameter_mm', 'mu_pivot_bushing'], 'catalog')
"""

from __future__ import annotations

import functools
import inspect
import math
import sys

import numpy as np

from synth import formatting as fmt
from synth.design.derivation_record import UNITS, Derivation, Quantity, Step, unit_of
from synth.design.trace import evaluator_lines, referenced, scalar, traced

__all__ = ["Derivation", "Quantity", "Step", "derive", "derivations", "derive_result", "check_names", "unit_of",
           "MAX_DEPTH"]

#: how deep a derivation follows the physics calls (a value's inputs, their inputs, ...)
MAX_DEPTH = 4

#: the catalog rows that hold a group's part attributes: table -> (part key, catalog file)
PART_CATALOGS = {
    "core": (("ball_bearing", "ball_bearings"), ("pivot_bushing_supplier", "pivot_bushings"),
             ("damper_pad_class", "damper_pads")),
    "bushing": (("pivot_bushing_supplier", "pivot_bushings"),),
    "axial": (("endcap_spacer_class", "endcap_spacers"),),
    "spring": (("main_spring_material", "spring_materials"), ("main_spring_wire", "spring_wires")),
    "bolt": (("bolt_format", "bolts"), ("bolt_head_type", "bolt_heads"), ("bolt_property_class", "bolt_property_classes")),
}

#: which catalog holds a part attribute: (attribute prefix, the part key, its catalog file), first match wins
ATTRIBUTE_CATALOGS = (
    ("bearing_", "ball_bearing", "ball_bearings"), ("pivot_bushing_", "pivot_bushing_supplier", "pivot_bushings"),
    ("damper_pad_", "damper_pad_class", "damper_pads"), ("endcap_spacer_", "endcap_spacer_class", "endcap_spacers"),
    ("bolt_head_", "bolt_head_type", "bolt_heads"), ("bolt_", "bolt_format", "bolts"),
    ("pivot_bore_", "bolt_format", "bolts"), ("rp02_", "bolt_property_class", "bolt_property_classes"),
    ("Rm_", "main_spring_material", "spring_material_strength"), ("E_", "main_spring_material", "spring_materials"),
    ("sigma_", "main_spring_material", "spring_materials"), ("supplied_in_section", "main_spring_material",
                                                            "spring_materials"),
    ("b_", "main_spring_wire", "spring_wires"), ("h_", "main_spring_wire", "spring_wires"),
    ("round_wire", "main_spring_wire", "spring_wires"),
)

# --------------------------------------------------------------------------------------------- explaining values
def _close(a, b) -> bool:
    if not isinstance(a, float) or not isinstance(b, float) or not (math.isfinite(a) and math.isfinite(b)):
        return isinstance(a, float) and isinstance(b, float) and a == b
    return a == b or abs(a - b) <= 1e-12 * max(abs(a), abs(b))


def _trivial(x) -> bool:
    return not isinstance(x, float) or x in (0.0, 1.0, -1.0) or not math.isfinite(x)


def _norm(name: str) -> str:
    return name.rstrip("_")


def _same_name(a: str, b: str) -> bool:
    """Whether two keys name one quantity: equal, or one ends with ``_`` and the other
    (``bushing_radial_thickness_mm`` of ``pivot_bushing_radial_thickness_mm``)."""
    a, b = _norm(a), _norm(b)
    return a == b or a.endswith("_" + b) or b.endswith("_" + a)


def _tokens(name: str) -> set:
    """The words of a key without its unit suffix (``middle_plane_belt_height_mm``: middle, plane, belt, height)."""
    n = _norm(name)
    for suffix, _ in UNITS:
        if n.endswith(suffix):
            n = n[: -len(suffix)]
            break
    return {w for w in n.split("_") if w}


def _distinctive(x) -> bool:
    """A value with at least 4 significant digits: matched by value alone (a round 20 or 0.5 is everywhere)."""
    if not isinstance(x, float) or not math.isfinite(x) or x == 0.0:
        return False
    digits = f"{abs(x):.12g}".split("e")[0].replace(".", "").lstrip("0").rstrip("0")
    return len(digits) >= 4


def _docstring_equation(module: str, name: str) -> str:
    """The equation of a physics function: its docstring's summary paragraph and ``.. math::`` lines."""
    mod = sys.modules.get(module)
    fn = getattr(mod, name, None) if mod else None
    doc = inspect.getdoc(fn) or ""
    paras = doc.split("\n\n")
    first = " ".join(paras[0].split()) if paras else ""
    maths = [" ".join(p.replace(".. math::", "").split()) for p in paras if ".. math::" in p]
    return " ".join([first] + [f"[{m}]" for m in maths if m]).replace("``", "")


class _Explainer:
    """Explains values of one traced evaluation (see :func:`derive`)."""

    def __init__(self, tracer, d, apps, attrs, values, parts):
        self.calls = [c for c in tracer.calls if c.end >= 0]
        self.d, self.apps, self.attrs, self.values, self.parts = d, apps, attrs, values, parts
        self.lines = evaluator_lines()
        self.shown: dict = {}
        self.constants, self.frictions = {}, {}
        for c in self.calls:
            v = scalar(c.result)
            if c.module == "synth.catalog" and isinstance(c.args.get("name"), str) and isinstance(v, float):
                self.constants.setdefault(c.args["name"], v)
            if c.module == "synth.parts" and isinstance(c.args.get("interface"), str) and isinstance(v, float):
                self.frictions.setdefault(c.args["interface"], v)
        self.sources: dict = {}
        from synth.schema import FIELDS
        self.fields = {f.name: f for f in FIELDS}

    # --- sources -----------------------------------------------------------------------------------------------
    def _given(self, f, value) -> bool:
        x = getattr(self.d, f.name, None)
        return isinstance(x, (int, float)) and not isinstance(x, bool) and _close(float(x), value)

    def _input(self, name, value, by_value: bool = False, context: str = ""):
        """The design input ``name`` is (by name; ``by_value``: the input holding ``value`` whose words best match
        ``name`` and the consuming function ``context``, e.g. ``belt_plane_height_mm`` of
        ``middle_plane_belt_height_mm``)."""
        if by_value:
            hits = [f for f in self.fields.values() if self._given(f, value)]
            want = _tokens(name) | _tokens(context)
            scored = sorted(((len(_tokens(f.name) & want), f) for f in hits), key=lambda t: -t[0])
            f = None
            if scored and not _trivial(value) and (len(scored) == 1 or scored[0][0] > scored[1][0]) \
                    and (scored[0][0] >= 2 or len(scored) == 1):
                f = scored[0][1]
        else:
            f = self.fields.get(_norm(name))
            if f is None:
                near = [x for n, x in self.fields.items() if _same_name(n, name)]
                given = [x for x in near if self._given(x, value)] or near
                f = max(given, key=lambda x: len(_tokens(x.name) & _tokens(context)), default=None)
        if f is None:
            return None
        given = getattr(self.d, f.name, None)
        label = f.label or f.name
        if isinstance(given, (int, float)) and not isinstance(given, bool) and _close(float(given), value):
            return Quantity(name, value, f.unit if f.unit != "-" else "", "input", f"design input {f.name} ({label})")
        col = self.apps.f.get(f.name) if hasattr(self.apps.f, "get") else None
        if given is None and col is not None and _close(float(np.asarray(col)[0]), value):
            return Quantity(name, value, f.unit if f.unit != "-" else "", "default",
                            f"documented default of design input {f.name} ({label}), not given")
        return None

    def _cite(self, where: str, source: str) -> str:
        """``where [n]``: the source's number in the derivation's list of sources (each cited once)."""
        n = self.sources.setdefault((where, source), len(self.sources) + 1)
        return f"{where} [{n}]"

    def _constant(self, name, value, by_name: bool = True):
        from synth import catalog
        hits = [n for n, v in self.constants.items() if _close(v, value) and _same_name(n, name)]
        if not hits and _is_constant(_norm(name)) and _close(catalog.constant(_norm(name)), value):
            hits = [_norm(name)]  # read before the trace (a cached table of constants)
        if not hits:
            return None
        pick = _norm(name) if _norm(name) in hits else hits[0]
        row = catalog.constant_row(pick)
        unit = str(row.get("unit", "") or "")
        return Quantity(name, value, "" if unit == "-" else unit, "constant",
                        self._cite(f"constant {pick} ({_constant_file(pick)})", str(row.get("source", ""))))

    def _friction(self, name, value):
        for interface, v in self.frictions.items():
            if _close(v, value) and (_norm(name) == f"mu_{interface}" or _norm(name).startswith("mu")):
                env = str(getattr(self.d, "application_type", "") or "")
                return Quantity(name, value, "", "catalog", self._cite(
                    f"catalogs/friction_coefficients.csv {interface}, {env}", _friction_source(interface, env)))
        return None

    def _part(self, name, value, by_value: bool = False):
        for k, v in self.parts.items():
            if (by_value or _same_name(k, name)) and isinstance(v, (int, float)) and not isinstance(v, bool) \
                    and _close(float(v), value) and not (by_value and _trivial(value)):
                f = self.fields.get(k)
                words = (f.label if f is not None and f.label else k.replace("_mm", "").replace("_", " ")).lower()
                return Quantity(name, value, unit_of(k), "design", f"the design's part: {words} ({k})")
        return None

    def _catalog_row(self, name, value):
        """A column of one of the design's catalog rows (the bolt's stress area, pitch...): by name, else by a
        distinctive value."""
        rows = _design_rows(tuple(sorted((k, str(v)) for k, v in self.parts.items() if isinstance(v, str))))
        for how in ("name", "words", "value"):
            for (where, src), cols in rows:
                for col, v in cols.items():
                    ok = _same_name(col, name) if how == "name" else (
                        len(_tokens(col) & _tokens(name)) >= 2 if how == "words" else _distinctive(value))
                    if _close(v, value) and ok:
                        return Quantity(name, value, unit_of(col) or unit_of(name), "catalog",
                                        f"{self._cite(where, src)}, column {col}")
        return None

    def _catalog(self, name, value):
        for table, cols in self.attrs.items():
            for col in (c for c in cols if _same_name(c, name)):
                v = scalar(np.asarray(cols[col]).reshape(-1)[0])
                if isinstance(v, float) and _close(v, value):
                    rows = _attribute_rows(col, table, self.parts)
                    q = Quantity(name, value, unit_of(name), "catalog", "")
                    q.source = "; ".join(self._cite(w, src) for w, src in rows) or f"the design's {table} data"
                    return q
        return None

    def _evaluator(self, name, value, before, depth):
        hit = self.lines.get(_norm(name))
        if hit is None:
            return None
        group, text, path = hit
        q = Quantity(name, value, unit_of(name), "evaluator",
                     f"computed by the evaluator's {group} group ({path})", formula=text)
        if depth < MAX_DEPTH:
            for k in referenced(text)[:6]:
                if k == _norm(name):
                    continue
                v = self._known(k)
                if v is not None:
                    q.parts.append(self.explain(k, v, before, depth + 1))
        if not q.parts:  # a value the group reads from a catalog table (a bushing's limits): its row
            row = self._catalog_row(name, value)
            if row is not None:
                q.parts.append(row)
        return q

    def _known(self, key):
        """The value of a key of the design (its values, its inputs, the application's fields, its parts' catalog
        attributes, or a named constant)."""
        v = self.values.get(key)
        for cols in self.attrs.values():
            if v is None and key in cols:
                v = np.asarray(cols[key]).reshape(-1)[0]
        if v is None and key in self.constants:
            v = self.constants[key]
        if v is None:
            v = getattr(self.d, key, None)
        if v is None and key in getattr(self.apps, "f", {}):
            v = np.asarray(self.apps.f[key])[0]
        return scalar(v)

    # --- the producing call ------------------------------------------------------------------------------------
    def _producer(self, name, value, before, *, named: bool):
        """The innermost physics call that returned ``value`` before event ``before`` (``named``: one whose function
        or output is called ``name``; else any, not a pass-through of one of its own inputs, never a trivial value)."""
        cands = []
        for c in self.calls:
            if c.module in ("synth.catalog", "synth.parts") or c.end >= before:
                continue
            for out_name, v in c.outputs:
                if not _close(v, value):
                    continue
                is_named = _same_name(name, c.name) or (out_name is not None and _same_name(name, out_name))
                if named != is_named or (not is_named and not _distinctive(value)):
                    continue
                if any(isinstance(a, float) and _close(a, value) for a in c.args.values()):
                    continue  # handed through (an argument returned as it came): not where it was computed
                cands.append((c.depth, c.end, c))
        if not cands:
            return None
        cands.sort(key=lambda t: (t[0], t[1]))
        best = cands[-1][2]
        # the innermost call inside it that computed the same value (a step's own equation: von Mises in the bolt's)
        inner = [c for c in self.calls if best.start < c.start and c.end < best.end and c.module.startswith("synth.model")
                 and any(_close(v, value) for _, v in c.outputs)
                 and not any(isinstance(a, float) and _close(a, value) for a in c.args.values())]
        return max(inner, key=lambda c: (c.depth, c.end)) if inner else best

    def explain(self, name: str, value, before: int | None = None, depth: int = 0, context: str = "") -> Quantity:
        """``name = value``: where it comes from (the producing physics call, an input, a constant, a catalog row, an
        evaluator line), following the physics calls ``MAX_DEPTH`` deep."""
        before = len(self.calls) * 10**9 if before is None else before
        v = scalar(value)
        if v is None or isinstance(v, (bool, str)):
            for prefix, key, table in ATTRIBUTE_CATALOGS:  # a part's yes/no attribute (a round wire): its row
                if _norm(name).startswith(prefix) and self.parts.get(key) not in (None, "none") \
                        and any(_norm(name) in cols for cols in self.attrs.values()):
                    return Quantity(name, v, "", "catalog", "; ".join(
                        self._cite(w, src) for w, src in _attribute_rows(_norm(name), "", self.parts)))
            return Quantity(name, v if v is not None else value, unit_of(name), "setting")
        if any(_norm(name) in cols for cols in self.attrs.values()) \
                and any(_norm(name).startswith(prefix) for prefix, _, _ in ATTRIBUTE_CATALOGS):
            q = self._catalog(name, v)  # a part's catalog attribute (a bolt class's Rp0.2): its row, not a pass-through
            if q is not None:
                return q
        if _is_constant(_norm(name)):  # a named catalog constant: its file, value and source
            q = self._constant(name, v)
            if q is not None:
                return q
        c = self._producer(name, v, before, named=True)
        if c is None:
            q = self._input(name, v, context=context) or self._part(name, v) or self._constant(name, v)
            if q is not None:
                return q
            for q in (self._friction(name, v), self._catalog(name, v)):
                if q is not None:
                    return q
            if _norm(name) in self.lines:
                return self._evaluator(name, v, before, depth)
            c = self._producer(name, v, before, named=False)
        if c is not None:
            q = Quantity(name, v, unit_of(name), "computed", c.qualname)
            if c.index in self.shown:
                q.source += " (derived above)"
                return q
            step = Step(c.qualname, _docstring_equation(c.module, c.name))
            self.shown[c.index] = step
            if depth < MAX_DEPTH:
                for k, a in c.args.items():
                    if isinstance(a, (float, bool, str)):
                        step.inputs.append(self.explain(k, a, c.start, depth + 1, c.name))
            q.step = step
            return q
        for q in (self._catalog_row(name, v), self._input(name, v, by_value=True, context=context),
                  self._part(name, v, by_value=True)):
            if q is not None:
                return q
        for c in self.calls:  # computed in the body of a call still running at the use (a spring's stresses)
            if c.start < before < c.end and c.module.startswith("synth.model"):
                outs = [k for k, x in c.outputs if k is not None and _close(x, v)]
                if outs:
                    return Quantity(name, v, unit_of(name), "computed",
                                    f"computed in the body of {c.qualname} (its output {outs[0]})")
        if _norm(name) in getattr(self.apps, "derived", {}):
            return Quantity(name, v, unit_of(name), "evaluator",
                            "derived from the design input (synth/design/applications.py)")
        return Quantity(name, v, unit_of(name), "value")


@functools.lru_cache(maxsize=None)
def _is_constant(name: str) -> bool:
    """Whether ``name`` is a named constant of the catalogs (``catalogs/constants*.csv``)."""
    from synth import catalog
    try:
        catalog.constant_row(name)
    except Exception:  # noqa: BLE001 - not a constant's name
        return False
    return True


@functools.lru_cache(maxsize=None)
def _constant_file(name: str) -> str:
    """The constants file that declares ``name`` (``constants_main_spring.csv``)."""
    from synth import catalog
    for n in catalog.names():
        if n == "constants" or n.startswith("constants_"):
            df = catalog.load(n)
            if name in set(df["name"]):
                return f"catalogs/{n}.csv"
    return "catalogs/constants*.csv"


def _row_source(name: str, key) -> str:
    from synth import catalog
    try:
        return str(catalog.row(name, str(key)).get("source", "") or "")
    except Exception:  # noqa: BLE001 - a key the catalog does not hold (a made part): no source row
        return ""


def _attribute_rows(attribute: str, table: str, parts: dict) -> list:
    """``[(where, source)]``: the catalog row(s) a design's part attribute comes from (:data:`ATTRIBUTE_CATALOGS`;
    else every part row of its table, :data:`PART_CATALOGS`)."""
    for prefix, key, name in ATTRIBUTE_CATALOGS:
        if attribute.startswith(prefix) and parts.get(key) not in (None, "none"):
            return [(f"catalogs/{name}.csv {parts[key]}", _row_source(name, parts[key]))]
    return [(f"catalogs/{name}.csv {parts[key]}", _row_source(name, parts[key]))
            for key, name in PART_CATALOGS.get(table, ()) if parts.get(key) not in (None, "none")]


@functools.lru_cache(maxsize=64)
def _design_rows(parts: tuple) -> list:
    """``[((where, source), {numeric column: value})]``: the catalog rows of a design's named parts
    (:data:`PART_CATALOGS`)."""
    from synth import catalog
    named = dict(parts)
    out, seen = [], set()
    for pairs in PART_CATALOGS.values():
        for key, name in pairs:
            k = named.get(key)
            if k in (None, "none") or (name, k) in seen:
                continue
            seen.add((name, k))
            try:
                row = catalog.row(name, k)
            except Exception:  # noqa: BLE001 - a made part: no catalog row
                continue
            cols = {}
            for col, v in row.items():
                try:
                    x = float(v)
                except (TypeError, ValueError):
                    continue
                if math.isfinite(x) and col != "source":
                    cols[str(col)] = x
            out.append(((f"catalogs/{name}.csv {k}", str(row.get("source", "") or "")), cols))
    return out


@functools.lru_cache(maxsize=None)
def _friction_source(interface: str, environment: str) -> str:
    from synth import catalog
    df = catalog.load("friction_coefficients")
    rows = df[(df["interface"].astype(str).str.strip() == interface)
              & df["environment"].astype(str).str.strip().isin([environment, "any"])]
    return str(rows.iloc[0]["source"]) if len(rows) else ""



# --------------------------------------------------------------------------------------------- the entry points
def _margin_formula(c, value: float, limit: float, scale, required: float) -> str:
    v, lim = fmt.number(value), fmt.number(limit)
    if c.scale is not None:
        s_text, s_name = fmt.number(scale), c.scale
    elif abs(limit) > 1e-9:
        s_text, s_name = fmt.number(abs(limit)), "|limit|"
    else:
        s_text, s_name = "1", "1 (a zero limit: the margin is the difference, in the check's unit)"
    diff = f"({lim} - {v})" if c.sense == "<=" else f"({v} - {lim})"
    head = "(limit - value)" if c.sense == "<=" else "(value - limit)"
    m = (limit - value if c.sense == "<=" else value - limit) / (float(scale) if c.scale is not None else
                                                                 (abs(limit) if abs(limit) > 1e-9 else 1.0))
    text = f"margin = {head} / {s_name} = {diff} / {s_text} = {fmt.percent(m)}"
    if required:
        text += f"; the design rule requires {fmt.percent(required, signed=False)}: {fmt.percent(m - required)} beyond it"
    return text


def check_names(ids, what: str = "check") -> list:
    """``ids`` (an id or a list of them) checked: each the id of a check the evaluator computes (a registry entry of
    an evaluated group), else an :class:`~synth.errors.InputError` naming ``what``, the id and every accepted id.

    >>> check_names("bolt_yield")
    ['bolt_yield']
    >>> check_names(["bolt_yeld"])
    Traceback (most recent call last):
    ...
    synth.errors.InputError: check: got 'bolt_yeld'; accepted: one of the design checks: pulley_axial_space, ...
    """
    from synth.design.constraints import EVALUATED_GROUPS, REGISTRY
    from synth.errors import InputError, Problem
    ids = [ids] if isinstance(ids, str) else list(ids)
    accepted = [k for k, x in REGISTRY.items() if x.group in EVALUATED_GROUPS]
    for cid in ids:
        if cid not in accepted:
            raise InputError(Problem(what, cid, "one of the design checks: " + ", ".join(accepted)))
    return ids


def derive(d, parts: dict, check_id: str, settings=None) -> Derivation:
    """The :class:`Derivation` of check ``check_id`` for design ``parts`` of input ``d`` under ``settings`` (the
    design rules in force apply, as for every evaluation). Unknown ids name the registry's."""
    return derivations(d, parts, [check_id], settings)[0]


def derivations(d, parts: dict, check_ids=None, settings=None) -> list:
    """The :class:`Derivation` of each of ``check_ids`` (default: every evaluated check of the design) from one
    traced evaluation of design ``parts`` of input ``d``."""
    from synth.design import evaluate
    from synth.design.applications import Applications
    from synth.design.constraints import REGISTRY
    from synth.design.result import checks_of
    from synth.design.space import space
    from synth.design.verify import evaluate_design, values_of
    ids = check_names(check_ids) if check_ids is not None else None
    settings = settings if settings is not None else evaluate.DEFAULT

    def run():
        apps = Applications.of([d])
        attrs = space().design_attributes(parts)
        return apps, attrs, evaluate_design(apps, attrs, settings)
    run()  # once without the hook: the catalogs and caches loaded at full speed
    (apps, attrs, groups), tracer = traced(run)
    values = values_of(groups, attrs)
    checks = {x.id: x for x in checks_of(groups, apps)}
    if ids is None:
        ids = [cid for cid, x in checks.items() if x.value is not None or x.note]
    out = []
    for cid in ids:
        ex = _Explainer(tracer, d, apps, attrs, values, parts)
        out.append(_derivation(REGISTRY[cid], checks[cid], groups, values, ex, settings.rules))
    return out


def _derivation(c, check, groups, values, ex, rules) -> Derivation:
    from synth.design.evaluate import CONSTANT_LIMITS
    g = groups[c.group].values

    def raw(key):
        if key in CONSTANT_LIMITS:
            return CONSTANT_LIMITS[key]
        return scalar(np.asarray(g[key]).reshape(-1)[0]) if key in g else values.get(key)
    value, limit = raw(c.value), raw(c.limit)

    def quantity(key, v):
        if key in CONSTANT_LIMITS:
            return Quantity(key, v, "", "constant", f"the registry's constant limit {key}")
        if key in rules.limits:
            return Quantity(key, v, c.unit if c.unit != "-" else "", "rule",
                            f"design rule {rules.name or 'unnamed'}: limit {key} = {fmt.number(v)}")
        q = ex.explain(key, v)
        if not q.unit and c.unit not in ("-", ""):
            q.unit = c.unit
        return q
    vq, lq = quantity(c.value, value), quantity(c.limit, limit)
    sq = quantity(c.scale, raw(c.scale)) if c.scale else None
    formula = ""
    if isinstance(value, float) and isinstance(limit, float) and math.isfinite(value) and math.isfinite(limit):
        formula = _margin_formula(c, value, limit, raw(c.scale) if c.scale else None, check.required)
    elif check.note:
        formula = check.note
    return Derivation(check=c.id, label=c.label, step=c.step, equation=c.equation, unit=c.unit, sense=c.sense,
                      verdict=check.verdict, margin=check.margin, margin_formula=formula,
                      required_margin=check.required, value=vq, limit=lq, scale=sq,
                      applies=c.applies or "", note=check.note,
                      sources=[(n, w, src) for (w, src), n in ex.sources.items()])


def derive_result(result, check_ids=None) -> list:
    """The derivations of checks ``check_ids`` (an id, a list, or None: every evaluated check) of a
    :class:`~synth.design.result.Result` (a synthesis, a saved ``--json``): its design evaluated again from its
    inputs and settings, under its own design rules."""
    from synth import schema
    from synth.design.settings import Settings
    from synth.errors import InputError, Problem
    if not result.parts or result.inputs is None:
        raise InputError(Problem("result", result.status, "a result with a design (parts) and its inputs"))
    settings = Settings.from_saved(result.settings, result.rules)  # the result's own configuration
    d = schema.validate({k: v for k, v in result.inputs.items() if v is not None})
    ids = [check_ids] if isinstance(check_ids, str) else check_ids
    return derivations(d, result.parts, ids, settings)
