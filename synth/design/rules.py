"""Design rules: a company's required safety factors and limits, minimum margins, the spring limit basis and
capability targets, read from one place and applied by the one evaluator.

A ``rules:`` section of the design input (beside ``inputs:`` in a case file, or a top-level key of a flat input
file) or a rules file (``--rules FILE``: the same mapping, at the top or under ``rules:``)::

    rules:
      name: ACME tensioner design rules, rev. C     # echoed in every output
      limits:                                      # required safety factors and limits
        main_spring_min_safety_factor: 1.3         # (registry limits that are catalog constants)
      min_margins:                                 # per check id: the margin a design must keep
        spring_yield: 5 %                          # (a fraction or a percentage)
      spring_limit_basis: thesis                   # the spring installation check's basis
      capability:                                  # targets of a production-scatter run (--capability)
        ppk_min: 1.33

* ``limits`` may tighten every registry limit that is a named catalog constant (:data:`LIMIT_NAMES`, derived
  from the registry and the catalogs: the Smith-Goodman safety factor, the spring index range, the coil gap, the
  arm and pivot walls, the cone spring's stress, the spring cavity): a minimum raised, a maximum lowered (to
  change the model's data, a user catalog: ``--catalogs``); the check then compares against the rule's value
  (shown as its limit).
* ``min_margins``: a check passes when its margin is at least the rule's; the margin every output shows is then
  the margin *beyond* the rule (``margin >= 0`` passes, everywhere: feasibility, the optimiser, the diagnosis),
  and the check carries the required margin (``required_margin``).
* ``spring_limit_basis`` and ``capability`` are the settings of the production-scatter and limit-basis work
  (issue 22): recorded, validated and echoed here; the spring limit basis lives here only
  (:attr:`synth.design.settings.Settings.spring_limit_basis` reads it).

Rules are part of a run's configuration (:class:`synth.design.settings.Settings`, its ``rules``): resolved once
where the run starts (the command line from ``--rules`` or the input file's section, the Python API from its
``rules=`` keyword or the input's section), passed as an argument to every search and worker, applied in
:func:`synth.design.evaluate.finish` and carried by every result (``Result.rules``), so a saved result is
re-verified under its own rules. No process-wide state: two threads judging under two sets of rules each get
their own.

>>> r = Rules.from_mapping({"name": "ACME", "min_margins": {"spring_yield": "5 %"},
...                         "limits": {"main_spring_min_safety_factor": 1.3}})
>>> r.min_margins, r.limits
({'spring_yield': 0.05}, {'main_spring_min_safety_factor': 1.3})
>>> echo(r)["name"], echo(NONE)
('ACME', {})
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.files import WORKBOOK_SUFFIXES, suffix_of
from synth.io.limits import short
from synth.io.structured import read_document
from synth.io.numbers import percentage

__all__ = ["Rules", "LIMIT_NAMES", "SPRING_LIMIT_BASES", "CAPABILITY_TARGETS", "read_rules",  # noqa: F822 (LIMIT_NAMES: module __getattr__)
           "NONE", "echo", "of_args"]

#: the bases of the main spring's installation check (issue 22 adds ``en13906``: the spring makers' static rule)
SPRING_LIMIT_BASES = ("thesis", "en13906")
#: capability targets a rule may set: the smallest process performance index Ppk, the largest share of
#: production outside a limit [ppm]
CAPABILITY_TARGETS = {"ppk_min": "smallest Ppk of every check", "ppm_max": "largest share outside a limit [ppm]"}
_KEYS = ("name", "limits", "min_margins", "spring_limit_basis", "capability")


@functools.lru_cache(maxsize=1)
def _limit_names() -> tuple[str, ...]:
    from synth import catalog
    from synth.design.constraints import REGISTRY
    names = set(catalog.constants_cached(())[0]["name"])
    return tuple(sorted({c.limit for c in REGISTRY.values() if c.limit in names}))


def __getattr__(name):  # LIMIT_NAMES derived on first use (the registry and the catalogs)
    if name == "LIMIT_NAMES":
        return _limit_names()
    raise AttributeError(name)


def _senses(name: str) -> set:
    from synth.design.constraints import REGISTRY
    return {c.sense for c in REGISTRY.values() if c.limit == name}


def _tightens(name: str, value: float) -> bool:
    """Whether a rule's ``value`` of limit ``name`` is at least as strict as the catalog's (a minimum raised, a
    maximum lowered): a design rule adds a requirement; changing the model's data is a user catalog's work
    (``--catalogs``), and the search's exact shortcuts (the spring kernels' option bounds) assume it."""
    from synth import catalog
    base = catalog.constant(name)
    senses = _senses(name)
    return (">=" not in senses or value >= base) and ("<=" not in senses or value <= base)


def _tighten_text(name: str) -> str:
    from synth import catalog
    word = "at least" if ">=" in _senses(name) else "at most"
    return (f"a value {word} the catalog's {catalog.constant(name):g} (a design rule tightens a limit; a user "
            "catalog, --catalogs, changes it)")


def _fraction(value, where: str) -> float:
    """A margin in [0, 1): a fraction (0.05) or a percentage (``"5 %"``, ``5%``, ``"0.5 %"`` is 0.005), read by the
    one percentage parser (:func:`synth.io.numbers.percentage`)."""
    x = percentage(value, "fraction")
    if x is None or not 0.0 <= x < 1.0:
        raise InputError(Problem(where, value, "a margin in [0, 1): a fraction (0.05) or a percentage below 100 % "
                                               "(5 %, 5%; \"0.5 %\" is 0.005)"))
    return x


@dataclass(frozen=True)
class Rules:
    """A set of design rules (see the module docstring); :data:`NONE` is the empty set."""

    name: str = ""
    source: str = ""
    limits: dict = field(default_factory=dict)
    min_margins: dict = field(default_factory=dict)
    spring_limit_basis: str = "thesis"
    capability: dict = field(default_factory=dict)

    def __hash__(self) -> int:  # frozen, of mappings: hashed by their items (a configuration is a cache key)
        return hash((self.name, self.source, tuple(sorted(self.limits.items())),
                     tuple(sorted(self.min_margins.items())), self.spring_limit_basis,
                     tuple(sorted(self.capability.items()))))

    def empty(self) -> bool:
        return not (self.limits or self.min_margins or self.capability or self.spring_limit_basis != "thesis")

    def targets(self) -> tuple:
        """The capability targets as ``(smallest Ppk, largest ppm)`` (:data:`CAPABILITY_TARGETS`; None: not set): what
        ``--capability``/``--ppm`` would say, for every entry point that reads them from the rules."""
        return self.capability.get("ppk_min"), self.capability.get("ppm_max")

    def required(self, cid: str) -> float:
        """The margin check ``cid`` must keep (0 without a rule)."""
        return self.min_margins.get(cid, 0.0)

    def as_dict(self) -> dict:
        return {"name": self.name, "source": self.source, "limits": dict(self.limits),
                "min_margins": dict(self.min_margins), "spring_limit_basis": self.spring_limit_basis,
                "capability": dict(self.capability)}

    def lines(self) -> list[str]:
        """The rules in words (every output echoes them)."""
        if self.empty():
            return []
        head = f"design rules: {self.name or 'unnamed'}" + (f" ({self.source})" if self.source else "")
        out = [head]
        out += [f"  limit {k} = {v:g}" for k, v in self.limits.items()]
        out += [f"  minimum margin {k}: {100 * v:g} %" for k, v in self.min_margins.items()]
        out.append(f"  spring limit basis: {self.spring_limit_basis}")
        out += [f"  capability {k} = {v:g} ({CAPABILITY_TARGETS[k]})" for k, v in self.capability.items()]
        return out

    @classmethod
    def from_mapping(cls, data, source: str = "rules") -> "Rules":
        """Rules of a mapping; every problem names the key (``rules.min_margins.spring_yld``), the value and what
        is accepted."""
        from synth.design.constraints import EVALUATED_GROUPS, REGISTRY
        if data is None:
            return NONE
        if isinstance(data, Rules):
            return data
        if not isinstance(data, dict):
            raise InputError(Problem(source, type(data).__name__, "a mapping of " + ", ".join(_KEYS)))
        problems = []
        for k in data:
            if k not in _KEYS and k != "source":
                problems.append(Problem(f"{source}.{k}", data[k], "one of " + ", ".join(_KEYS)))

        def mapping(key) -> dict:
            v = data.get(key) or {}
            if not isinstance(v, dict):
                problems.append(Problem(f"{source}.{key}", v, "a mapping"))
                return {}
            return v
        limits = {}
        for k, v in mapping("limits").items():
            if k not in _limit_names():
                problems.append(Problem(f"{source}.limits.{k}", v, "a limit a rule may set: " + ", ".join(_limit_names())))
            elif isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
                problems.append(Problem(f"{source}.limits.{k}", v, "a finite number >= 0"))
            elif not _tightens(k, float(v)):
                problems.append(Problem(f"{source}.limits.{k}", v, _tighten_text(k)))
            else:
                limits[k] = float(v)
        margins = {}
        for k, v in mapping("min_margins").items():
            c = REGISTRY.get(k)
            if c is None or c.group == "input" or c.group not in EVALUATED_GROUPS or c.advisory:
                problems.append(Problem(f"{source}.min_margins.{k}", v, "the id of a design check of the registry "
                                        "(not an input-only, advisory, 3D-model or shrink-fit one)"))
                continue
            try:
                margins[k] = _fraction(v, f"{source}.min_margins.{k}")
            except InputError as exc:
                problems += exc.problems
        basis = str(data.get("spring_limit_basis") or "thesis").strip().lower()
        if basis not in SPRING_LIMIT_BASES:
            problems.append(Problem(f"{source}.spring_limit_basis", data.get("spring_limit_basis"),
                                    " or ".join(SPRING_LIMIT_BASES)))
        cap = {}
        for k, v in mapping("capability").items():
            if k not in CAPABILITY_TARGETS:
                problems.append(Problem(f"{source}.capability.{k}", v, "one of " + ", ".join(CAPABILITY_TARGETS)))
            elif isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                problems.append(Problem(f"{source}.capability.{k}", v, "a positive finite number"))
            else:
                cap[k] = float(v)
        name = data.get("name") or ""
        if not isinstance(name, str):
            problems.append(Problem(f"{source}.name", name, "a text"))
        if problems:
            raise InputError(problems)
        return cls(str(name).strip(), str(data.get("source") or source), limits, margins, basis, cap)


NONE = Rules()


def echo(rules: Rules) -> dict:
    """``rules`` as a result and a run's manifest carry them (``Result.rules``; {} without rules)."""
    return {} if rules.empty() else rules.as_dict()


#: what ``--rules`` accepts (every refusal of a rules file says it)
_RULES_ACCEPTED = ("a YAML, TOML or JSON file of design rules (keys " + ", ".join(_KEYS) + ", at the top or under "
                   "rules:), or a design input or saved result with a rules: section")


def _read_rules_mapping(path, what: str, *, section_only: bool):
    """The design-rules mapping of file ``path``: a design input's (or a saved result's) ``rules:`` section, or a
    rules file's mapping (at the top, or under ``rules:``).

    ``section_only`` (a design input read for its own rules): the ``rules:`` section or None (a workbook has
    none; the input's own reader reports what is wrong with the file). Otherwise (``--rules FILE``) the file must
    hold rules, judged by its content: a workbook, a design input or saved result without a ``rules:`` section,
    or a mapping with none of the rules' keys is refused naming the file, what it is and what is accepted.
    """
    if section_only:
        if suffix_of(path) in WORKBOOK_SUFFIXES:
            return None
        try:
            data = read_document(path, what, accepted=_RULES_ACCEPTED)
        except InputError:
            return None
        return data.get("rules") or None if isinstance(data, dict) else None
    data = read_document(path, what, accepted=_RULES_ACCEPTED)  # a workbook, PDF, binary...: refused by content
    if not isinstance(data, dict):
        held = "nothing (it is empty)" if data is None else f"a {type(data).__name__}, not a mapping"
        raise InputError(Problem(what, str(path), f"{_RULES_ACCEPTED}; this file holds {held}"))
    if data.get("rules"):
        return data["rules"]
    result = data.get("kind") == "synth.result" or "checks" in data
    if "rules" in data or result or "inputs" in data or not any(k in _KEYS and k != "name" for k in data):
        what_it_is = ("a saved result made without design rules" if result
                      else "a design input without a rules: section" if "inputs" in data or "application_type" in data
                      else "a file whose rules: section is empty" if "rules" in data
                      else "a file without design rules")
        keys = ", ".join(sorted(map(str, data))[:6]) or "none"
        raise InputError(Problem(what, str(path), f"{_RULES_ACCEPTED}; this is {what_it_is} (its keys: "
                                                  f"{short(keys, 100)})"))
    return data


def read_rules(path, what: str = "--rules", *, section_only: bool = False) -> Rules:
    """The rules of a file: a rules file (the mapping at the top, or under ``rules:``) or a design input's (or a
    saved result's) ``rules:`` section (none: :data:`NONE`); through the input gate."""
    data = _read_rules_mapping(path, what, section_only=section_only)
    if data is None:
        return NONE
    return Rules.from_mapping(data, source=data.get("source") if isinstance(data, dict) and data.get("source")
                              else f"{Path(path).name}" + (": rules" if section_only else ""))


def of_args(args) -> Rules:
    """The rules of a scene's command line: ``--rules FILE``, else the ``rules:`` section of its input file (a
    scene that takes design rules registers ``--rules``: :func:`synth.scenes._options.add_model_options`)."""
    if not hasattr(args, "rules"):
        return NONE
    if args.rules:
        return read_rules(args.rules)
    src = getattr(args, "input", None)
    if isinstance(src, str) and src.lower().endswith((".yaml", ".yml", ".toml", ".json")):
        if Path(src).is_file():
            return read_rules(src, "input file", section_only=True)
    return NONE
