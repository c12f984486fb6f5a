"""One designer's state in ``synth ui``: the form's texts, the validated input, the design and its result.

Every number comes from the public API (:func:`synth.synthesise`, :func:`synth.verify`,
:func:`synth.write_report`, :func:`synth.cad.export_result`); this module keeps what the page shows in
step: an edit re-validates the whole input (:func:`synth.schema.validate`, the command line's messages)
and, when it is valid, re-verifies the current design at once; "synthesise" runs the optimiser and makes
its design the current one, and its ranked alternatives stay on offer (:meth:`DesignSession.apply` makes one the
current design). A what-if sweep (:meth:`DesignSession.sweep`) verifies the current design along one input. The 3D
model, graphs, report and capability are made by the worker processes (:mod:`synth.ui.work`) from
:meth:`DesignSession.key`, the session's name for the result in view.

The design rules of the input (its ``rules:`` section, :func:`synth.design.rules.read_rules`, as the command line
reads them) are the session's own: every synthesis and verification gets them as its ``rules=`` argument, never
through a process-wide setting (two tabs of one server judge under their own rules).

>>> s = DesignSession(default_values(), source="default")
>>> s.synthesise().verdict, s.result.parts["ball_bearing"]
('pass', '6006')
>>> s.edit("pulley_diameter_mm", "500"), s.problems["pulley_diameter_mm"]
(False, ['pulley_diameter_mm: got 500; accepted: a number in [10, 200] mm'])
>>> s.edit("pulley_diameter_mm", "62"), s.result.status
(True, 'verified')
>>> [a["rank"] for a in s.alternatives][:2], s.apply(2).parts == s.alternatives[1]["parts"], s.applied
([1, 2], True, 2)
"""

from __future__ import annotations

import copy
import math
import secrets
import tempfile
from importlib import resources
from pathlib import Path
from typing import Any

import synth
from synth import schema
from synth.io import documents
from synth.design.rules import NONE, Rules, read_rules
from synth.errors import InputError, Problem
from synth.ui import form

__all__ = ["DesignSession", "default_values", "offered_objectives", "FIDELITIES", "TOP", "TOP_MAX", "SWEEP_POINTS"]

#: the alternatives a synthesis in the page lists by default (``Result.alternatives``), and the most it offers
TOP, TOP_MAX = 5, 20


def offered_objectives() -> tuple:
    """The objectives the page offers: every declared goal (:data:`synth.optimise.objectives.OBJECTIVES`, read when
    the page draws, so a goal declared with :func:`synth.optimise.objectives.declare` is offered too); a
    lexicographic or weighted one stays the API's. The registry module imports numpy and the errors only."""
    from synth.optimise import objectives
    return objectives.OBJECTIVES


#: what opening an input (:meth:`DesignSession.set_values`) leaves in a session: the boxes' texts, the validated input
#: and the problems (:meth:`DesignSession.opened_state`)
OPENED = ("texts", "input", "problems", "other_problems")

#: the model fidelities (:data:`synth.design.evaluate.FIDELITIES`; ``full`` is every design scene's default)
FIDELITIES = ("full", "screening")
#: the points of a what-if sweep, and the most a page asks for
SWEEP_POINTS, SWEEP_MAX = 21, 101


def default_values() -> dict:
    """The embedded default application (``synth/data/default_case.yaml``, what ``synth demo`` designs)."""
    path = resources.files("synth").joinpath("data/default_case.yaml")
    with resources.as_file(path) as p:
        return documents.read_mapping(p)


class DesignSession:
    """The state of one design page (see the module docstring)."""

    def __init__(self, values: dict | None = None, *, source: str = "", workdir: str | Path | None = None,
                 rules: Rules | dict | None = None, opened: dict | None = None):
        """``opened``: what a session opened on the same ``values``, ``source`` and ``rules`` left
        (:meth:`opened_state`; the server's launch hands over its worker's, :class:`synth.ui.launch.Launch`), taken
        instead of validating again."""
        self.texts: dict[str, str] = {f.name: "" for f in schema.FIELDS}
        self.source = source
        self.rules: Rules = Rules.from_mapping(rules, source=f"{source}: rules") if rules else NONE
        self.objective, self.fidelity = "standard", "full"
        self.input = None
        self.problems: dict[str, list[str]] = {}
        self.other_problems: list[str] = []
        self.result = None
        self.seq = 0  # +1 at every evaluation: the page's "result shown" counter
        self.top = TOP
        self.alternatives: list[dict] = []  # the last synthesis's ranked designs (Result.alternatives)
        self.applied: int | None = None     # the rank of the alternative in view (1: the optimum), None: edited
        self.uid = secrets.token_hex(6)     # the session's part of the worker's keys (:meth:`key`)
        self._workdir = Path(workdir) if workdir else None
        if opened is None:
            self.set_values(values or {})
        else:
            for name in OPENED:
                setattr(self, name, copy.deepcopy(opened[name]))

    def opened_state(self) -> dict:
        """What opening the input left (:data:`OPENED`: the boxes' texts, the validated input, the problems)."""
        return {name: getattr(self, name) for name in OPENED}

    @property
    def workdir(self) -> Path:
        """The session's folder (its uploads, template, reports): the one given, else a temporary one made when first
        asked for (a session a worker opens to synthesise makes none)."""
        if self._workdir is None:
            self._workdir = Path(tempfile.mkdtemp(prefix="synth-ui-"))
        return self._workdir

    # --- the input ----------------------------------------------------------------------------------------------
    def set_values(self, values: dict, source: str | None = None) -> bool:
        """Replace every box by ``values`` (a mapping as a file gives it) and validate; True if valid."""
        known = {f.name for f in schema.FIELDS}
        aliases = {a: f.name for f in schema.FIELDS for a in f.aliases}
        self.texts = {f.name: "" for f in schema.FIELDS}
        unknown = {}
        for k, v in values.items():
            name = aliases.get(str(k), str(k))
            if name in known:
                self.texts[name] = form.text_of(v)
            else:
                unknown[str(k)] = v
        if source is not None:
            self.source = source
        ok = self.validate(extra=unknown)
        if ok:  # a drop-down shows the choice a thesis word means ("Autosetting" is single_eccentric)
            for f in schema.FIELDS:
                if f.choices and self.texts[f.name] and getattr(self.input, f.name) is not None:
                    self.texts[f.name] = getattr(self.input, f.name)
        return ok

    def validate(self, extra: dict | None = None) -> bool:
        """Validate the boxes (and ``extra`` fields the form has no box for: they are reported, not kept)."""
        try:
            data = {**form.mapping(self.texts), **(extra or {})}
            self.input = schema.validate(data)
            self.problems, self.other_problems = {}, []
            return True
        except InputError as e:
            self.input = None
            self.problems, self.other_problems = form.problems_by_field(e)
            return False

    def values(self) -> dict[str, Any]:
        """The input as typed (``{field: value}``; what "save YAML" writes)."""
        return form.mapping(self.texts)

    def edit(self, name: str, text: Any) -> bool:
        """Set one box; re-validate and, when valid and a design exists, re-verify it. True if the input is valid."""
        if name not in self.texts:
            raise InputError(Problem("field", name, "a design-input field of synth.schema"))
        self.texts[name] = "" if text is None else str(text)
        if not self.validate():
            return False
        if self.result is not None and self.result.parts:
            self.verify()
        return True

    def read(self, path: str | Path) -> tuple[dict, Rules]:
        """The values and the design rules (its ``rules:`` section; none: no rules) of an input file (YAML, TOML,
        JSON, the Excel template), as the command line reads them; an :class:`~synth.errors.InputError` for a file
        that cannot be read or whose rules are not valid."""
        values = documents.read_mapping(Path(path))
        rules = read_rules(Path(path), "input file", section_only=True)
        return {k: v for k, v in values.items() if v is not None}, rules

    def open(self, values: dict, rules: Rules, source: str) -> bool:
        """Take an input read by :meth:`read` (the form's values and the rules); True if it is valid."""
        self.rules = rules
        return self.set_values(values, source=source)

    def load(self, path: str | Path) -> bool:
        """Fill the form from an input file and take its design rules (:meth:`read`, :meth:`open`); synthesise when
        it is valid. A readable file with bad values fills the form and marks the fields."""
        if self.open(*self.read(path), Path(path).name):
            self.synthesise()
            return True
        return False

    def yaml_text(self) -> str:
        return form.to_yaml(self.values(), self.source, rules=self.rules)

    def rule_lines(self) -> list[str]:
        """The design rules the session judges by, in words (none: empty)."""
        return self.rules.lines()

    def write_template(self, path: str | Path) -> Path:
        """The Excel input template filled with the (valid) input: ``synth template --from``."""
        from synth.excel.template import write_template
        self._require_valid()
        return write_template(path, self.input.as_dict())

    def _require_valid(self) -> None:
        if self.input is None:
            raise InputError([Problem(k, None, "; ".join(v)) for k, v in self.problems.items()]
                             or [Problem("input", None, "; ".join(self.other_problems) or "a valid design input")])

    # --- the design -------------------------------------------------------------------------------------------
    def synthesise(self):
        """The optimiser's design for the input (``synth.synthesise``, its :attr:`top` best); it becomes the current
        design, its alternatives those on offer."""
        self._require_valid()
        return self.adopt(synth.synthesise(self.input, self.objective, fidelity=self.fidelity, top=self.top,
                                           rules=self.rules))

    def synthesis_call(self) -> tuple:
        """``(input, rules, objective, fidelity, top)``: the arguments of :meth:`synthesise`'s call (a worker makes
        the same call: :func:`synth.ui.work.synthesise`)."""
        self._require_valid()
        return self.input, self.rules, self.objective, self.fidelity, self.top

    def adopt(self, result):
        """Make ``result`` (of :meth:`synthesise`'s call) the current design and its alternatives those on offer."""
        self.result = result
        self.alternatives = list(result.alternatives or [])
        self.applied = 1 if self.alternatives else None
        self.seq += 1
        return result

    def verify(self, parts: dict | None = None):
        """The current design (or ``parts``) checked for the current input (``synth.verify``)."""
        self._require_valid()
        if parts is None and (self.result is None or not self.result.parts):
            return self.synthesise()
        self.result = synth.verify(self.input, dict(parts or self.result.parts), fidelity=self.fidelity,
                                   rules=self.rules)
        if parts is None:  # an edit: the design in view is no longer one of the ranked ones as they were ranked
            self.applied = None
        self.seq += 1
        return self.result

    def apply(self, rank: int):
        """Make alternative ``rank`` (1: the optimum) of the last synthesis the current design, verified for the
        current input."""
        ranks = [a["rank"] for a in self.alternatives]
        if isinstance(rank, bool) or rank not in ranks:
            raise InputError(Problem("alternative", rank, "the rank of an alternative on offer: "
                                     + (", ".join(map(str, ranks)) or "none (synthesise first)")))
        alt = self.alternatives[ranks.index(rank)]
        self.verify(alt["parts"])
        self.applied = rank
        return self.result

    def key(self) -> str:
        """The name of the result in view for the worker's caches (the session and its evaluation)."""
        return f"{self.uid}-{self.seq}"

    def application(self) -> str | None:
        """The application's name for the STEP product and the report: the input's file name without its suffix."""
        stem = Path(self.source).stem if self.source else ""
        return stem or None

    # --- what if --------------------------------------------------------------------------------------------------
    def sweep_range(self, name: str) -> tuple[float, float]:
        """The default range of a what-if sweep of field ``name``: its value +-20 %, inside what it accepts."""
        f = self._numeric_field(name)
        x0 = float(getattr(self.input, name))
        lo, hi = (x0 * 0.8, x0 * 1.2) if x0 > 0 else (x0 * 1.2, x0 * 0.8) if x0 < 0 else (-1.0, 1.0)
        span = hi - lo
        lo = max(lo, f.lo + (1e-6 * span if f.lo_open else 0.0))
        hi = min(hi, f.hi - (1e-6 * span if f.hi_open else 0.0))
        return lo, hi

    def sweep_fields(self) -> list[str]:
        """The input fields a what-if sweep can move: the numbers the current input gives."""
        if self.input is None:
            return []
        return [f.name for f in schema.FIELDS if f.kind in ("float", "int") and not f.choices and not f.catalog
                and isinstance(getattr(self.input, f.name, None), (int, float))
                and not isinstance(getattr(self.input, f.name), bool)]

    def _numeric_field(self, name: str):
        if name not in self.sweep_fields():
            raise InputError(Problem("sweep input", name, "a number of the current input: "
                                     + ", ".join(self.sweep_fields()[:8]) + ", ..."))
        return schema.field_by_name(name)

    def sweep(self, name: str, lo: float, hi: float, points: int = SWEEP_POINTS) -> dict:
        """The current design verified (``synth.verify``) at ``points`` values of input ``name`` from ``lo`` to
        ``hi``, the rest of the input as it is: ``{"field", "x", "design_x", "margins": {check: [margin or None]},
        "verdicts": {check: [verdict]}}``, margins as fractions (the evaluator's); a value the input refuses is a
        point without margins."""
        self._require_valid()
        if self.result is None or not self.result.parts:
            raise InputError(Problem("design", None, "a design to sweep (synthesise first)"))
        f = self._numeric_field(name)
        ok = all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in (lo, hi))
        if not ok or not lo < hi:
            raise InputError(Problem("sweep range", f"{lo} to {hi}", "two finite numbers, the first the smaller"))
        if isinstance(points, bool) or not isinstance(points, int) or not 3 <= points <= SWEEP_MAX:
            raise InputError(Problem("sweep points", points, f"an integer in [3, {SWEEP_MAX}]"))
        xs = [lo + (hi - lo) * i / (points - 1) for i in range(points)]
        if f.kind == "int":
            xs = sorted({int(round(x)) for x in xs})
        base, parts = self.input.as_dict(), dict(self.result.parts)
        margins: dict[str, list] = {}
        verdicts: dict[str, list] = {}
        for j, x in enumerate(xs):
            try:
                r = synth.verify({**base, name: x}, parts, fidelity=self.fidelity, rules=self.rules)
                got = {c.id: c for c in r.checks}
            except InputError:
                got = {}
            for cid in set(margins) | set(got):
                c = got.get(cid)
                margins.setdefault(cid, [None] * len(xs))[j] = (
                    None if c is None or c.margin is None or not math.isfinite(c.margin) else float(c.margin))
                verdicts.setdefault(cid, [None] * len(xs))[j] = None if c is None else c.verdict
        return {"field": name, "x": xs, "design_x": float(getattr(self.input, name)), "margins": margins,
                "verdicts": verdicts}
