"""The one verdict of a result: every target the user set, decided once (issue 35).

A design's verdict reads what its result holds:

* its checks (the registry's, judged by the assessment: a design rule's limit or minimum margin is already in the
  check's margin, so a rule missed is a failed check);
* its production capability, where a capability target was set (``--capability``, ``--ppm`` or the design
  rules' ``capability:``): :attr:`Result.robust <synth.design.result.Result.robust>` says whether every counted
  check meets it (``meets``) and which do not (``failing``);
* the design rules' capability target when no capability was computed (a target set and not assessed);
* the checks not verified (data missing) and the documented defaults assumed.

The states and exit codes (every scene, the report's digest, the results workbook, the bulk rows and the web page
read them from here):

* ``fail`` (exit 1): a check fails, or a capability target set is missed;
* ``incomplete`` (exit 3): nothing fails, but a check was not verified, an input took its documented default, or
  a capability target of the design rules was not assessed;
* ``pass`` (exit 0): every check passes and every target set is met.

:class:`Verdict` carries the state and its reasons in words (one line each, worst first) and the one-line form
every scene prints last (:meth:`Verdict.line`).

>>> v = judge([], robust={"checks": [{"id": "under_head", "label": "under-head pressure", "target": True,
...     "meets": False, "ppk": 0.945, "p_hi": 0.0036}], "meets": False, "targets": "Ppk >= 1.33",
...     "failing": ["under_head"]})
>>> v.state, v.exit_code
('fail', 1)
>>> v.line()
'Verdict: FAIL (production capability Ppk >= 1.33 missed: under-head pressure Ppk 0.945; every nominal check passes)'
"""

from __future__ import annotations

from dataclasses import dataclass, field

from synth import formatting as fmt
from synth.design.assessment import EVALUATED_VERDICTS, FAIL, INCOMPLETE, NOT_VERIFIED, PASS, verdict_of

__all__ = ["Verdict", "Reason", "judge", "combine", "EXIT_CODES", "capability_missed", "target_text"]

#: a design's verdict -> the exit code of every scene
EXIT_CODES = {PASS: 0, FAIL: 1, INCOMPLETE: 3}


@dataclass(frozen=True)
class Reason:
    """One reason of a verdict: ``kind`` (``check``: a failed check; ``target``: a capability target missed;
    ``not assessed``: a target set and not computed; ``not verified``; ``assumed``), the words, and the check ids it
    concerns."""

    kind: str
    text: str
    checks: tuple = ()

    def as_dict(self) -> dict:
        return {"kind": self.kind, "text": self.text, "checks": list(self.checks)}


@dataclass(frozen=True)
class Verdict:
    """A result's verdict (see the module docstring): ``state`` (``pass``, ``fail``, ``incomplete``) and its
    ``reasons`` (worst first)."""

    state: str
    reasons: tuple = field(default_factory=tuple)

    @property
    def exit_code(self) -> int:
        return EXIT_CODES[self.state]

    @property
    def failed(self) -> bool:
        return self.state == FAIL

    def missed_targets(self) -> list:
        """The reasons that are a capability target missed or not assessed."""
        return [r for r in self.reasons if r.kind in ("target", "not assessed")]

    def summary(self) -> str:
        """The reasons in one clause each, ``;``-separated: what the last line says after the state."""
        parts = []
        checks = [r for r in self.reasons if r.kind == "check"]
        if checks:
            parts.append(f"{len(checks)} check{'s' if len(checks) > 1 else ''} failed, worst: {checks[0].text}")
        parts += [r.text for r in self.reasons if r.kind in ("target", "not assessed")]
        if self.state != FAIL and any(r.kind == "target_met" for r in self.reasons):
            parts += [r.text for r in self.reasons if r.kind == "target_met"]
        nv = [r for r in self.reasons if r.kind == "not verified"]
        if nv:
            parts.append(f"{len(nv)} not verified")
        assumed = [r for r in self.reasons if r.kind == "assumed"]
        if assumed:
            parts.append(f"{len(assumed)} input{'s' if len(assumed) > 1 else ''} assumed")
        if self.state == FAIL and not checks:
            parts.append("every nominal check passes")
        return "; ".join(parts)

    def line(self) -> str:
        """``Verdict: PASS``, ``Verdict: FAIL (...)`` or ``Verdict: INCOMPLETE (...)``: the last line of every scene
        that judges a design."""
        word = {PASS: "PASS", FAIL: "FAIL", INCOMPLETE: "INCOMPLETE"}[self.state]
        s = self.summary()
        return f"Verdict: {word}" + (f" ({s})" if s else "")

    def as_dict(self) -> dict:
        """The verdict as data (``Result.to_dict()["verdict_detail"]``: what the web page reads)."""
        return {"state": self.state, "exit_code": self.exit_code, "line": self.line(),
                "reasons": [r.as_dict() for r in self.reasons if r.kind != "target_met"],
                "targets_met": [r.text for r in self.reasons if r.kind == "target_met"]}


def combine(nominal: str, target_missed: bool = False, target_unassessed: bool = False) -> str:
    """A verdict from the nominal one (of the checks) and the capability target: a target missed fails the design,
    a target set and not assessed leaves a passing design incomplete; the rows of ``synth bulk --capability`` and
    :func:`judge` apply this one rule.

    >>> combine("pass", target_missed=True), combine("pass", target_unassessed=True), combine("fail")
    ('fail', 'incomplete', 'fail')
    """
    return verdict_of(nominal == FAIL or bool(target_missed),
                      nominal == INCOMPLETE or bool(target_unassessed))


def target_text(robust: dict) -> str:
    """The capability target of a capability result (``Ppk >= 1.33``, ``<= 10 ppm``...)."""
    return str(robust.get("targets") or "the capability target")


def capability_missed(robust: dict) -> bool:
    """Whether a capability result (``Result.robust``) holds a target that is missed."""
    return bool(robust and robust.get("checks") and not robust.get("meets", True))


def _capability_reason(robust: dict) -> Reason:
    by_id = {c["id"]: c for c in robust.get("checks", [])}
    failing = [by_id[i] for i in robust.get("failing", []) if i in by_id]
    failing.sort(key=lambda c: (c.get("ppk") if c.get("ppk") is not None else float("inf")))
    ppm = (robust.get("settings") or {}).get("ppm")

    def one(c) -> str:
        text = f"{c.get('label', c['id'])} Ppk {fmt.number(c.get('ppk'), 3)}"
        if ppm is not None and c.get("p_hi") is not None:
            text += f", up to {fmt.probability(c['p_hi'])}"
        return text
    words = "; ".join(one(c) for c in failing) or "see the capability table"
    return Reason("target", f"production capability {target_text(robust)} missed: {words}",
                  tuple(c["id"] for c in failing))


def _check_reason(c) -> Reason:
    return Reason("check", fmt.check_words(c), (c.id,))


def judge(checks: list, robust: dict | None = None, rules: dict | None = None) -> Verdict:
    """The :class:`Verdict` of a design's ``checks`` (:class:`~synth.design.result.Check` records), its capability
    ``robust`` (``Result.robust``; {} or None: none computed) and the design ``rules`` it was judged by
    (``Result.rules``: a ``capability`` target there with no capability computed is a target not assessed)."""
    robust = robust or {}
    failed = sorted((c for c in checks if c.verdict == FAIL),
                    key=lambda c: c.margin if c.margin is not None else float("-inf"))
    reasons = [_check_reason(c) for c in failed]
    missed = capability_missed(robust)
    if missed:
        reasons.append(_capability_reason(robust))
    elif robust.get("checks") and robust.get("targets") not in (None, "", "none"):
        reasons.append(Reason("target_met", f"production capability {target_text(robust)} met"))
    target = (rules or {}).get("capability") or {}
    unassessed = bool(target) and not robust.get("checks")
    if unassessed:
        words = ", ".join(f"{k} {fmt.number(v)}" for k, v in target.items())
        reasons.append(Reason("not assessed", f"the design rules' capability target ({words}) was not assessed "
                                              "(synth robust, or --capability, computes it)"))
    nv = [c for c in checks if c.verdict == NOT_VERIFIED]
    reasons += [Reason("not verified", f"{c.constraint.label}: {c.note or 'not verified'}", (c.id,)) for c in nv]
    assumed = list(dict.fromkeys(a for c in checks if c.verdict in EVALUATED_VERDICTS for a in c.assumed))
    reasons += [Reason("assumed", a) for a in assumed]
    nominal = verdict_of(bool(failed), bool(nv or assumed))
    return Verdict(combine(nominal, missed, unassessed), tuple(reasons))
