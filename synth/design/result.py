"""One result type for every scene: the design, its values, one check per registry constraint, the verdict.

:class:`Result` is what the flowchart, every solver, the bulk engine (per
row), the report, the workbooks and the CAD export read and write: the part
keys (:data:`synth.design.space.PART_KEYS`), the derived values, a
:class:`Check` per constraint of :data:`synth.design.constraints.REGISTRY`,
notes, the inputs and settings (so a saved JSON is self-contained), and the
solver's status, objectives and statistics when a solver made it.

Verdicts (:attr:`Result.verdict`, exit codes of :attr:`Result.exit_code`):

* ``pass`` (exit 0): every constraint was checked with the data given, and passes;
* ``incomplete`` (exit 3): nothing fails, but some checks were not verified
  (missing optional data) or used a documented default for a missing input;
* ``fail`` (exit 1): a check fails.

Advisory constraints (the thesis's Table 7 ranges) never fail a design; a
value outside them is a warning.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field


from synth import display
from synth.design.assessment import (EVALUATED, EVALUATED_VERDICTS, FAIL, INCOMPLETE, NOT_APPLICABLE as NOT_APPLICABLE_STATE,
                                     NOT_APPLICABLE_VERDICT as NOT_APPLICABLE, NOT_VERIFIED, PASS, WARNING, Assessment,
                                     assess, check_verdict)
from synth.design.constraints import GROUPS as REGISTRY_GROUPS, REGISTRY, margin as registry_margin
from synth.io.outputs import plain  # JSON-friendly data (NaN and infinities as None, no subnormal number)
from synth.design.applications import DEFAULTS
from synth.design.evaluate import CONSTANT_LIMITS as CONSTANT_LIMITS
from synth.design.verdict import Verdict, judge
from synth.schema import FIELDS
from synth.errors import InputError, Problem
from synth.catalog import constant

__all__ = ["Check", "Result", "PASS", "FAIL", "INCOMPLETE", "NOT_VERIFIED", "NOT_APPLICABLE", "WARNING", "plain",
           "checks_of", "row_verdict", "field_corrections", "absent_part", "part_note"]



#: significant figures of the numbers a result exports (JSON): 6, beyond what any input or catalog value carries
EXPORT_DIGITS = 6



@dataclass
class Check:
    """One registry constraint evaluated for one design.

    ``verdict``: ``pass``, ``fail``, ``warning`` (an advisory constraint
    outside its range), ``not verified`` (data missing: ``note`` says which)
    or ``not applicable``. ``assumed`` lists the documented defaults it used.
    """

    id: str
    value: float | None
    limit: float | None
    margin: float | None
    verdict: str
    note: str = ""
    assumed: list = field(default_factory=list)
    #: the margin a design rule requires of this check (``margin`` is then the margin beyond it)
    required: float = 0.0

    @classmethod
    def judged(cls, cid: str, value, limit, note: str = "") -> "Check":
        """The check of constraint ``cid`` from its value and limit, for a scene that computes them apart from the
        evaluator's groups (the shrink fit, :mod:`synth.shrink_fit.analysis`): the registry's margin
        (:func:`~synth.design.constraints.margin`) and verdict (:func:`~synth.design.assessment.check_verdict`); a value or limit None is not
        verified.

        >>> c = Check.judged("shrink_fit_hub_elastic", 107.8, 155.1)
        >>> round(c.margin, 3), c.verdict
        (0.305, 'pass')
        """
        if value is None or limit is None:
            return cls(cid, None, None, None, NOT_VERIFIED, note)
        c = REGISTRY[cid]
        m = float(registry_margin(c, value, limit))
        return cls(cid, float(value), float(limit), m, check_verdict(c, m), note)

    @property
    def constraint(self):
        return REGISTRY[self.id]

    @property
    def label(self) -> str:
        return self.constraint.label

    @property
    def step(self) -> int:
        return self.constraint.step

    def as_dict(self, digits: int | None = None) -> dict:
        c = self.constraint
        return {"id": self.id, "label": c.label, "step": c.step, "equation": c.equation, "unit": c.unit,
                "sense": c.sense, "value": plain(self.value, digits), "limit": plain(self.limit, digits),
                "margin": plain(self.margin, digits), "verdict": self.verdict, "advisory": c.advisory,
                "correction": c.correction if self.verdict == FAIL else "", "note": self.note,
                "assumed": list(self.assumed), "required_margin": self.required}


@dataclass
class Result:
    """The one result of synth (see the module docstring).

    ``status``: ``verified`` (a given design checked), ``baseline`` (the thesis
    flowchart's own design), ``optimal`` (proved by a solver), ``feasible``
    (an anytime solver's best), ``infeasible`` (then ``diagnosis`` says what
    binds, by how much, and the smallest input change that fixes it).
    """

    status: str
    solver: str = "flowchart"
    objective: str = ""
    parts: dict = field(default_factory=dict)
    values: dict = field(default_factory=dict)
    checks: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    objectives: dict = field(default_factory=dict)
    stats: dict = field(default_factory=dict)
    diagnosis: dict | None = None
    inputs: dict | None = None
    settings: dict = field(default_factory=dict)
    steps_run: list = field(default_factory=list)
    curves: dict = field(default_factory=dict)
    #: production capability (synth.robust): tolerance model, per check P(violation), Ppk, worst case, RSS
    robust: dict = field(default_factory=dict)
    #: the parts the input names that the design does not keep, one dict each (field, input, design, how, why:
    #: :func:`synth.optimise.honour.changes_of`)
    changes: list = field(default_factory=list)
    #: which named parts were fixed, free, kept when possible and freed (:func:`synth.optimise.honour.solve_honouring`)
    control: dict = field(default_factory=dict)
    #: the K best designs in objective order, the first this one (``--top K``:
    #: :func:`synth.optimise.alternatives.ranked`): rank, parts, objectives, margin, binding, verdict, differs
    alternatives: list = field(default_factory=list)
    #: the design's price lines (quoted, modelled, assumed) and, for the cost objective, how much the choice
    #: depends on the prices (:func:`synth.cost.decision.cost_report`)
    cost: dict = field(default_factory=dict)
    #: the design rules the checks were made under (:mod:`synth.design.rules`; {} without rules)
    rules: dict = field(default_factory=dict)

    # --- verdicts ------------------------------------------------------------------------------------------
    def failed(self) -> list:
        return [c for c in self.checks if c.verdict == FAIL]

    def not_verified(self) -> list:
        return [c for c in self.checks if c.verdict == NOT_VERIFIED]

    def warnings(self) -> list:
        return [c for c in self.checks if c.verdict == WARNING]

    def assumptions(self) -> list:
        """The documented defaults used by evaluated checks, once each."""
        return list(dict.fromkeys(a for c in self.checks if c.verdict in EVALUATED_VERDICTS for a in c.assumed))

    def assessment(self) -> Assessment:
        """The one-design :class:`~synth.design.assessment.Assessment` of the checks (what the margins mean)."""
        return Assessment.of_checks(self.checks, self.values)

    @property
    def judgement(self) -> Verdict:
        """The one :class:`~synth.design.verdict.Verdict` of this result: its checks, every target the user set
        (the capability target of :attr:`robust`, the design rules'), what was not verified or assumed, and why."""
        return judge(self.checks, self.robust, self.rules)

    @property
    def verdict(self) -> str:
        """``pass``, ``fail`` or ``incomplete``: :attr:`judgement`'s state (a capability target missed fails)."""
        return self.judgement.state

    @property
    def exit_code(self) -> int:
        return self.judgement.exit_code

    @property
    def feasible(self) -> bool:
        """Every checked constraint passes (advisory ones aside)."""
        return not self.failed()

    @property
    def margins(self) -> dict:
        """``{constraint id: margin}`` of the evaluated non-advisory checks (an advisory check's margin is on the
        check itself, :meth:`check`; it never enters feasibility)."""
        on = self.assessment().counted[0]
        return {c.id: c.margin for c, x in zip(self.checks, on) if x and c.margin is not None}

    def check(self, cid: str) -> Check:
        for c in self.checks:
            if c.id == cid:
                return c
        raise KeyError(cid)

    def get(self, key: str, default=None):
        """A part or a value by its key (one vocabulary for both)."""
        if key in self.parts:
            return self.parts[key]
        return self.values.get(key, default)

    def binding(self, n: int = 8) -> list:
        """The ``n`` smallest margins of the binding candidates (the assessment's: evaluated objective checks)."""
        a = self.assessment()
        on = a.binding_candidates[0]
        order = sorted((j for j in range(len(self.checks)) if on[j]), key=lambda j: a.margins[0, j])
        return [self.checks[j] for j in order[:n]]

    #: what a synthesis adds to a verified design (kept when the design is verified again, e.g. for its curves)
    SYNTHESIS_FIELDS = ("objective", "objectives", "stats", "diagnosis", "changes", "control", "alternatives", "cost")

    def carry(self, other: "Result") -> "Result":
        """This result with the synthesis fields (:attr:`SYNTHESIS_FIELDS`) of ``other``; returns self."""
        for k in self.SYNTHESIS_FIELDS:
            setattr(self, k, getattr(other, k))
        return self

    # --- presentation ------------------------------------------------------------------------------------------
    def to_frame(self):
        """The checks as a pandas DataFrame, one row per registry constraint (index: the constraint id).

        Columns: label, step, equation, unit, sense, value, limit, margin (floats: NaN where not evaluated, an
        infinite limit kept), verdict, advisory, correction (of a failed check), note, assumed.
        """
        import pandas as pd
        cols = ["id", "label", "step", "equation", "unit", "sense", "value", "limit", "margin", "verdict",
                "advisory", "correction", "note", "assumed"]
        rows = [{**c.as_dict(), "value": c.value, "limit": c.limit, "margin": c.margin} for c in self.checks]
        df = pd.DataFrame(rows, columns=cols).set_index("id")
        return df.astype({k: float for k in ("value", "limit", "margin")})  # an infinite limit stays infinite

    def _repr_html_(self) -> str | None:
        """What a notebook shows: the view the presentation layer registered (:mod:`synth.display`: the report's
        digest of verdict, failing checks, warnings, not verified, assumed)."""
        return display.html(self)

    # --- serialisation ---------------------------------------------------------------------------------------
    def to_dict(self, digits: int | None = EXPORT_DIGITS) -> dict:
        """The result as JSON data: margins as fractions, numbers to ``digits`` significant figures (the parts,
        inputs and settings exactly: a saved design is verified again from them)."""
        n = digits
        return {
            "kind": "synth.result", "status": self.status, "verdict": self.verdict,
            "verdict_detail": self.judgement.as_dict(), "solver": self.solver,
            "objective": self.objective, "parts": plain(self.parts), "values": plain(self.values, n),
            "checks": [c.as_dict(n) for c in self.checks], "notes": list(self.notes),
            "objectives": plain(self.objectives, n), "stats": plain(self.stats, n), "diagnosis": plain(self.diagnosis, n),
            "inputs": plain(self.inputs), "settings": plain(self.settings), "steps_run": list(self.steps_run),
            **({"robust": plain(self.robust, n)} if self.robust else {}),
            "changes": plain(self.changes), "control": plain(self.control), "alternatives": plain(self.alternatives, n),
            **({"cost": plain(self.cost, n)} if self.cost else {}),
            "rules": plain(self.rules),
        }

    @classmethod
    def from_dict(cls, data: dict, source: str = "result") -> "Result":
        """A result from :meth:`to_dict`'s output (a saved ``--json``); wrong shapes name the key."""
        if not isinstance(data, dict):
            raise InputError(Problem(source, type(data).__name__, "a JSON object written by synth (--json)"))
        for key, kind in (("parts", dict), ("values", dict), ("checks", list)):
            if not isinstance(data.get(key), kind):
                raise InputError(Problem(f"{source}: {key}", type(data.get(key)).__name__,
                                         f"a JSON {'object' if kind is dict else 'list'} (a result written by synth)"))
        checks = []
        for i, c in enumerate(data["checks"]):
            if not isinstance(c, dict) or c.get("id") not in REGISTRY:
                raise InputError(Problem(f"{source}: checks[{i}].id", c.get("id") if isinstance(c, dict) else c,
                                         "a constraint id of synth's registry"))
            checks.append(Check(c["id"], c.get("value"), c.get("limit"), c.get("margin"), c.get("verdict", ""),
                                c.get("note", ""), list(c.get("assumed") or []), float(c.get("required_margin") or 0.0)))
        return cls(status=str(data.get("status", "verified")), solver=str(data.get("solver", "")),
                   objective=str(data.get("objective", "")), parts=dict(data["parts"]), values=dict(data["values"]),
                   checks=checks, notes=list(data.get("notes") or []), objectives=dict(data.get("objectives") or {}),
                   stats=dict(data.get("stats") or {}), diagnosis=data.get("diagnosis"),
                   inputs=data.get("inputs"), settings=dict(data.get("settings") or {}),
                   steps_run=list(data.get("steps_run") or []), changes=list(data.get("changes") or []),
                   control=dict(data.get("control") or {}), alternatives=list(data.get("alternatives") or []),
                   rules=dict(data.get("rules") or {}),
                   robust=dict(data["robust"]) if isinstance(data.get("robust"), dict) else {},
                   cost=dict(data["cost"]) if isinstance(data.get("cost"), dict) else {})


def checks_of(groups: dict, apps, row: int = 0, assessment: Assessment | None = None) -> list:
    """The :class:`Check` records of one design: row ``row`` of each evaluated group (registry order), judged by
    the assessment of the groups (:func:`synth.design.assessment.assess`; ``assessment``: one the caller made of
    every row, then ``row`` indexes it)."""
    a = assessment if assessment is not None else assess(groups, apps, rows=slice(row, row + 1))
    j = row if assessment is not None else 0
    app = {}
    for name, g in groups.items():  # the application of the row in each group (row i is application i without)
        if name in REGISTRY_GROUPS:
            app[name] = int(g.values["app"][row]) if "app" in g.values else row
    out = []
    for k, c in enumerate(a.columns.constraints):
        cid, g, st, aa = c.id, groups[c.group], int(a.state[j, k]), app[c.group]
        if st == NOT_APPLICABLE_STATE:
            out.append(Check(cid, None, None, None, NOT_APPLICABLE))
            continue
        if st != EVALUATED:
            if apps is None:
                out.append(Check(cid, None, None, None, NOT_VERIFIED, f"not verified: {c.limit} not given"))
                continue
            missing = [r for r in c.needs if not apps.met(r)[aa]]
            out.append(Check(cid, None, None, None, NOT_VERIFIED, apps.missing_note(missing[0], aa) if missing else ""))
            continue
        value = float(g.values[c.value][row])
        limit = CONSTANT_LIMITS[c.limit] if c.limit in CONSTANT_LIMITS else float(g.values[c.limit][row])
        m = float(a.margins[j, k])
        verdict = FAIL if a.failed[j, k] else (WARNING if a.warning[j, k] else PASS)
        assumed = [] if apps is None or not a.assumed[j, k] else [
            apps.assumed_note(x, aa) for x in c.assumes if x in DEFAULTS and apps.assumed(x)[aa]]
        out.append(Check(cid, value, limit, m, verdict, assumed=assumed, required=g.rules.required(cid)))
    return out


#: value-key prefix -> the part whose absence (class ``none``) makes those values not applicable
_ABSENT_WITH = {"damper_pad_": "damper_pad_class", "endcap_spacer_": "endcap_spacer_class",
                "cone_spring_": "endcap_spacer_class"}


def absent_part(parts: dict, key: str) -> bool:
    """Whether part key ``key`` of design ``parts`` belongs to a part the design does not have (the cone spring's
    ratios and diameters without an endcap spacer: stored as 0, shown as ``none``).

    >>> absent_part({"endcap_spacer_class": "none", "cone_spring_aspect_ratio": 0.0}, "cone_spring_aspect_ratio")
    True
    """
    return key not in _ABSENT_WITH.values() and any(key.startswith(prefix) and (parts or {}).get(part) == "none"
                                                    for prefix, part in _ABSENT_WITH.items())


def part_note(result: Result, key: str) -> str:
    """What a part key's value means where it is not itself a quantity of the made tensioner, for every medium that
    lists the parts: the pivot class is thesis Table 2's class (the arm's bore for a 1 mm bushing wall), not the
    pivot's diameter, which is ``class + 2 (t_ref - t)`` (:func:`synth.model.pivot.pivot_diameter_mm`, step 2).
    Empty where the key needs no note or the values are missing.

    >>> r = Result("optimal", parts={"pivot_class_diameter_mm": 20.0},
    ...            values={"pivot_diameter_mm": 21.0, "pivot_bushing_radial_thickness_mm": 0.5})
    >>> part_note(r, "pivot_class_diameter_mm")
    'Table 2 class; pivot diameter 21 mm = class + 2 x (1 mm - 0.5 mm bushing wall)'
    """
    if key != "pivot_class_diameter_mm":
        return ""
    v = result.values or {}
    d, t = v.get("pivot_diameter_mm"), v.get("pivot_bushing_radial_thickness_mm")
    if not all(isinstance(x, (int, float)) and math.isfinite(x) for x in (d, t)):
        return ""
    t_ref = constant("pivot_reference_bushing_thickness_mm")
    return f"Table 2 class; pivot diameter {d:g} mm = class + 2 x ({t_ref:g} mm - {t:g} mm bushing wall)"


def _not_applicable_value(result: Result, key: str, readers: list) -> bool:
    """A missing value the design does not have: every check reading it does not apply, or its part is ``none``."""
    if readers:
        return all(v == NOT_APPLICABLE for v in readers)
    if key == "axial_damping_nm":
        return result.values.get("axial_damping_present") is False
    return absent_part(result.parts, key)


def row_verdict(result: Result, key: str) -> str | None:
    """The verdict of an output-table row: the worst of the checks that compare this value (registry ``value``
    or ``limit`` keys), or None when no check reads it. A missing value is ``not applicable`` where the design
    has no such value (the checks reading it do not apply, or its part is ``none``), else ``not verified``.

    >>> r = Result("verified", parts={"damper_pad_class": "none"}, values={"main_spring_sigma_inst_mpa": 1500.0},
    ...            checks=[Check("spring_yield", 1500.0, 1400.0, -0.07, FAIL)])
    >>> row_verdict(r, "main_spring_sigma_inst_mpa"), row_verdict(r, "pulley_width_mm")
    ('fail', 'not verified')
    >>> row_verdict(r, "damper_pad_contact_area_mm2")
    'not applicable'
    """
    v = result.get(key)
    readers = [c.verdict for c in result.checks if key in (c.constraint.value, c.constraint.limit)]
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return NOT_APPLICABLE if _not_applicable_value(result, key, readers) else NOT_VERIFIED
    mine = [x for x in readers if x != NOT_APPLICABLE]
    for verdict in (FAIL, WARNING, NOT_VERIFIED, PASS):
        if verdict in mine:
            return verdict
    return None


def field_corrections(result: Result) -> dict:
    """Suggested correction per input field (thesis column G), from the registry.

    A failed check suggests its correction for the input fields its value or limit is (or the smallest
    relaxation of the diagnosis names); a not-verified check asks for the fields it needs.
    """
    names = {f.name for f in FIELDS}
    out: dict = {}
    for c in result.checks:
        con = c.constraint
        if c.verdict == FAIL:
            for k in (con.value, con.limit):
                if k in names:
                    out.setdefault(k, []).append(f"{con.correction} ({con.label})" if con.correction else con.label)
        elif c.verdict == NOT_VERIFIED and c.note.startswith("not verified"):
            for k in con.requirement_fields():
                if (result.inputs or {}).get(k) is None:
                    out.setdefault(k, []).append(f"give a value to verify: {con.label}")
    for rel in (result.diagnosis or {}).get("relaxations", [])[:3]:
        for k, ch in rel["inputs"].items():
            out.setdefault(k, []).append(f"{ch['from']:g} -> {ch['to']:g} makes a design feasible")
    return {k: "; ".join(dict.fromkeys(v)) for k, v in out.items()}
