"""One designer's state in ``synth ui``: the form's texts, the validated input, the design and its result.

Every number comes from the public API (:func:`synth.synthesise`, :func:`synth.verify`,
:func:`synth.write_report`, :func:`synth.cad.export_result`); this module keeps what the page shows in
step: an edit re-validates the whole input (:func:`synth.schema.validate`, the command line's messages)
and, when it is valid, re-verifies the current design at once; "synthesise" runs the optimiser and makes
its design the current one. Files (the 3D model, the report) are written once per evaluated result into
the session's own folder.

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
"""

from __future__ import annotations

import tempfile
from importlib import resources
from pathlib import Path
from typing import Any

import synth
from synth import schema
from synth.io import documents
from synth.design.rules import NONE, Rules, read_rules
from synth.errors import InputError, Problem
from synth.optimise.objectives import OBJECTIVES
from synth.ui import form
from synth.excel.template import write_template
from synth.cad import export_result

__all__ = ["DesignSession", "default_values", "OBJECTIVES", "FIDELITIES"]

#: the alternatives a synthesis in the page lists (``Result.alternatives``)
TOP = 5
#: the objectives offered (``synth.synthesise``'s documented ones; a lexicographic or weighted one stays the API's):
#: :data:`synth.optimise.objectives.OBJECTIVES`, imported above
#: the model fidelities (:data:`synth.design.evaluate.FIDELITIES`; ``full`` is every design scene's default)
FIDELITIES = ("full", "screening")


def default_values() -> dict:
    """The embedded default application (``synth/data/default_case.yaml``, what ``synth demo`` designs)."""
    path = resources.files("synth").joinpath("data/default_case.yaml")
    with resources.as_file(path) as p:
        return documents.read_mapping(p)


class DesignSession:
    """The state of one design page (see the module docstring)."""

    def __init__(self, values: dict | None = None, *, source: str = "", workdir: str | Path | None = None,
                 rules: Rules | dict | None = None):
        self.texts: dict[str, str] = {f.name: "" for f in schema.FIELDS}
        self.source = source
        self.rules: Rules = Rules.from_mapping(rules, source=f"{source}: rules") if rules else NONE
        self.objective, self.fidelity = "standard", "full"
        self.input = None
        self.problems: dict[str, list[str]] = {}
        self.other_problems: list[str] = []
        self.result = None
        self.seq = 0  # +1 at every evaluation: the page's "result shown" counter
        self.workdir = Path(workdir) if workdir else Path(tempfile.mkdtemp(prefix="synth-ui-"))
        self._files: dict[tuple, dict] = {}
        self.set_values(values or {})

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
        self._require_valid()
        return write_template(path, self.input.as_dict())

    def _require_valid(self) -> None:
        if self.input is None:
            raise InputError([Problem(k, None, "; ".join(v)) for k, v in self.problems.items()]
                             or [Problem("input", None, "; ".join(self.other_problems) or "a valid design input")])

    # --- the design -------------------------------------------------------------------------------------------
    def synthesise(self):
        """The optimiser's design for the input (``synth.synthesise``); it becomes the current design."""
        self._require_valid()
        self.result = synth.synthesise(self.input, self.objective, fidelity=self.fidelity, top=TOP, rules=self.rules)
        self.seq += 1
        return self.result

    def verify(self):
        """The current design checked for the current input (``synth.verify``)."""
        self._require_valid()
        if self.result is None or not self.result.parts:
            return self.synthesise()
        self.result = synth.verify(self.input, self.result.parts, fidelity=self.fidelity, rules=self.rules)
        self.seq += 1
        return self.result

    # --- files ---------------------------------------------------------------------------------------------------
    def _folder(self, kind: str, seq: int) -> Path:
        p = self.workdir / f"{kind}-{seq}"
        p.mkdir(parents=True, exist_ok=True)
        return p

    def cad(self) -> dict:
        """The 3D model of the current result (STEP, one STL per part, section and exploded pictures): paths."""
        seq, result = self.seq, self.result  # an edit while the model is built makes a new result, not this one
        key = ("cad", seq)
        if key not in self._files:
            out = self._folder("cad", seq)
            model, checks, info = export_result(result, out, application=self.source or None)
            self._files[key] = {"step": out / "tensioner.step", "section": out / "section.png",
                                "exploded": out / "exploded.png",
                                "stl": {f.stem: f for f in info["files"] if f.suffix == ".stl"},
                                "checks": checks, "folder": out}
        return self._files[key]

    def report(self, pdf: bool = False) -> dict:
        """The report of the current result (``synth.write_report``: HTML and workbook, and the PDF when ``pdf``;
        Chromium prints it in about 2 s, so only when asked): paths."""
        seq, result = self.seq, self.result
        key = ("report", seq, pdf)
        if key not in self._files:
            self._files[key] = synth.write_report(result, self._folder("report-pdf" if pdf else "report", seq), pdf=pdf)
        return self._files[key]
