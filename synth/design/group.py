"""The evaluator's groups: the :class:`Group` of values and registry margins, :func:`finish` (values to margins, with
"not applicable" and "not verified" from the registry), the checks' own physics (:func:`add_physics`) and what each
group reads of its core row (:func:`core_values`).

Every group function of the one evaluator (:mod:`synth.design.evaluate`) ends in :func:`finish`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from synth import catalog, schema
from synth.design.assessment import EVALUATED, NOT_APPLICABLE, NOT_VERIFIED_STATE as NOT_VERIFIED, assess_group
from synth.design.constraints import by_group, margin, physics_inputs
from synth.design.rules import NONE as NO_RULES, Rules
from synth.errors import DeclarationError, Problem

__all__ = ["CONSTANT_LIMITS", "Group", "finish", "add_physics", "const", "Fields", "BUSHING_CORE_VALUES",
           "AXIAL_CORE_VALUES", "SPRING_KEY_VALUES", "BOLT_CORE_VALUES", "core_values", "read_core", "EVALUATED",
           "NOT_APPLICABLE", "NOT_VERIFIED", "unreadable", "pinned_table"]

CONSTANT_LIMITS = {"zero": 0.0, "one": 1.0}  # limits (and scales) that are plain numbers


@dataclass
class Group:
    """Values and registry margins of one group's rows (``(n,)`` arrays).

    ``margins[id]`` is ``+inf`` where the constraint does not apply or is not
    verified (``state`` says which), ``-inf`` where its value is NaN. ``search``: the search model's group
    this one was judged from (:func:`axial_judged`); its margins rank nearest designs (:meth:`rank`). ``rules``:
    the design rules its margins are measured beyond (:meth:`synth.design.rules.Rules.required`).
    """

    name: str
    values: dict
    margins: dict = field(default_factory=dict)
    state: dict = field(default_factory=dict)
    search: "Group | None" = None
    #: the design rules the margins were computed under (:func:`finish`): each check's required margin
    rules: Rules = NO_RULES

    def rank(self) -> "Group":
        """The group whose margins rank nearest designs: the search model's (:attr:`search`), else this one."""
        return self.search if self.search is not None else self

    def __len__(self) -> int:
        return len(next(iter(self.values.values()))) if self.values else 0

    def assessment(self):
        """The :class:`~synth.design.assessment.Assessment` of this group's rows (the one judgement of margins)."""
        return assess_group(self)

    def ok(self) -> np.ndarray:
        """``(n,)`` bool: every (non-advisory) constraint of the group passes."""
        return self.assessment().ok

    def min_margin(self, objective_only: bool = True) -> np.ndarray:
        """``(n,)`` smallest margin of the constraints counted in the margin objective (or all non-advisory)."""
        a = self.assessment()
        return a.objective_margin if objective_only else a.margin_min

    def put(self, rows, other: "Group") -> "Group":
        """A copy whose rows ``rows`` are ``other``'s rows (a group of the same function, ``len(rows)`` rows)."""
        def mix(a: dict, b: dict) -> dict:
            out = {}
            for k, v in a.items():
                if k.startswith("_"):
                    out[k] = v
                    continue
                arr = np.array(v, copy=True)
                arr[rows] = b[k]
                out[k] = arr
            return out
        return Group(self.name, mix(self.values, other.values), mix(self.margins, other.margins),
                     mix(self.state, other.state), rules=self.rules)

    def take(self, idx) -> "Group":
        """The rows ``idx`` as a new group."""
        return Group(self.name, {k: v[idx] for k, v in self.values.items()},
                     {k: v[idx] for k, v in self.margins.items()}, {k: v[idx] for k, v in self.state.items()},
                     rules=self.rules)


def finish(name: str, values: dict, apps, a, checks: tuple | None = None, *, rules: Rules = NO_RULES,
           core: dict | None = None) -> Group:
    """The registry margins of group ``name`` (or of its ``checks`` only) from its ``values`` for rows of
    applications ``a`` (an array of any shape: every value broadcasts to it).

    ``apps`` may be None (a group measured on a built model, the CAD checks): a constraint that needs an input
    is then not verified where its limit is NaN. ``rules`` (the configuration's,
    :attr:`synth.design.settings.Settings.rules`) set the limits they name and the margins checks must keep: the
    margin is then the one beyond the rule's. ``core``: the values of the rows' core the group's checks may read
    (:func:`core_values`), for their physics functions (:func:`add_physics`).
    """
    n = np.shape(a)  # the rows' shape: 1-D, or the bulk engine's 2-D grid of core rows x bolt diameters
    margins, state = {}, {}
    met = {}
    checks = by_group(name) if checks is None else checks
    add_physics(checks, values, apps, a, core)
    for c in checks:
        if c.limit in rules.limits:  # a design rule sets this limit (synth.design.rules)
            values[c.limit] = np.full(n, rules.limits[c.limit])
        lim = CONSTANT_LIMITS[c.limit] if c.limit in CONSTANT_LIMITS else values[c.limit]
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            scale = None if c.scale is None else (CONSTANT_LIMITS[c.scale] if c.scale in CONSTANT_LIMITS
                                                  else values[c.scale])
            m = margin(c, values[c.value], lim, scale)
            kept = rules.required(c.id)
            if kept:  # the margin beyond the rule's (x - 0.0 is x: no copy without a rule)
                m = m - kept
        undefined = np.isnan(m)
        if undefined.any():
            m = np.where(undefined, -np.inf, m)
        own = m.shape == n  # an array of the group's rows, new (the margin's), else a scalar or a broadcast
        m = m if own else np.broadcast_to(m, n)
        st = np.zeros(n, dtype=np.int8)
        if c.applies is not None:
            st[~np.asarray(values[c.applies], dtype=bool)] = NOT_APPLICABLE
        if apps is None:
            if c.needs:
                st[(st == EVALUATED) & np.isnan(np.broadcast_to(np.asarray(lim, dtype=float), n))] = NOT_VERIFIED
        else:
            for req in c.needs:
                if req not in met:
                    met[req] = apps.met(req)[a]
                st[(st == EVALUATED) & ~met[req]] = NOT_VERIFIED
        # every row evaluated (the usual case): the margins as they are, in an array of their own
        margins[c.id] = m if own and not st.any() else np.where(st == EVALUATED, m, np.inf)
        state[c.id] = st
    return Group(name, values, margins, state, rules=rules)


def add_physics(checks, values: dict, apps, a, core: dict | None = None) -> None:
    """The values and limits of the ``checks`` that declare a physics function (:attr:`Constraint.physics`), added
    to ``values`` in place: each parameter is read by its name from the group's values, else from its core's
    (``core``: the rows' core values, :func:`core_values`), else from the applications' fields at rows ``a``, but
    for a field that pins another part family's part (:func:`pinned_table`); a name that is none of them is an error
    naming the check (:func:`unreadable`)."""
    for c in checks:
        if c.physics is not None:
            kw = {}
            for k in physics_inputs(c):
                if k in values:
                    kw[k] = values[k]
                elif core is not None and k in core:
                    kw[k] = core[k]
                elif apps is not None and k in apps.f and pinned_table(k) in ("", "core", c.group):
                    kw[k] = apps.f[k][a]
                else:  # another family's part is not the application's field that can pin it (mostly unset)
                    raise unreadable(c, k)
            values.update(c.physics(**kw))


def pinned_table(name: str) -> str:
    """The design-space table whose part the input field ``name`` pins (:attr:`synth.schema.Field.pins`: the spring
    for ``main_spring_mean_body_diameter_mm``), "" for a field that pins none. A check of another group that reads it
    would read the application's pin (NaN where the input leaves the part to the search), not the design's part."""
    return _PINS.get(name, "")


_PINS = {f.name: f.pins[0] for f in schema.FIELDS if f.pins}


def unreadable(c, name: str) -> DeclarationError:
    """The error of check ``c`` whose physics reads ``name``, which its group does not have: a configuration error
    (the check's declaration, a plug-in's or the user's), not synth's and not one application's, so
    :class:`~synth.errors.DeclarationError` (the command line's exit 2), never a ``KeyError``. A check reads a value
    of its own group, of its core or an application field: each part family is chosen apart from the others given
    its core (:mod:`synth.design.subsystems`), so a check that reads another family's part (a bolt check reading the
    main spring's wire) would couple two searches the decomposition keeps apart, and every path refuses it alike
    (``tests/test_conformance.py``, read kind "other")."""
    return DeclarationError(Problem(f"constraint {c.id} (group {c.group}): its physics function's parameter", name,
                                    f"a value of group {c.group}, of its core or a field of the application; a "
                                    "check cannot read another part family's value (each family is chosen apart "
                                    "given the core): declare it on values its group has"))


def const(name: str) -> float:
    return catalog.constant(name)


class Fields(dict):
    """The applications' numeric fields at rows ``a``, gathered on first access (a group reads a handful of the
    many fields; gathering them all for every row was most of the cost of a large chunk)."""

    def __init__(self, apps, a):
        super().__init__()
        self._f, self._a = apps.f, a

    def __missing__(self, key):
        v = self[key] = self._f[key][self._a]
        return v


#: what the bushing group's function reads of its core row (besides the application): declared beside the function;
#: :func:`core_values` adds what the registry's checks read
BUSHING_CORE_VALUES = ("hubload_nominal_n", "pivot_diameter_mm", "axial_group_present")
#: what the axial group's function reads of its core row (besides the application)
AXIAL_CORE_VALUES = ("axial_damping_nm", "radial_damping_nm",
                     "cone_spring_max_external_diameter_mm", "cone_spring_min_internal_diameter_mm",
                     "cone_spring_table8_max_mm", "damper_pad_mean_radius_mm", "damper_pad_contact_area_mm2",
                     "damper_pad_axial_height_mm", "bearing_width_mm", "axial_group_present",
                     "damper_pad_outer_diameter_mm")
#: what a main spring reads of its core row (besides the application): its key
SPRING_KEY_VALUES = ("spring_torque_nominal_nm", "spring_housing_height_mm", "spring_housing_outer_diameter_mm",
                     "spring_housing_inner_diameter_mm")
#: what the bolt group's function reads of its core row: nothing (step 10 sees the application and the bolt); its
#: checks that read the core (the pivot wall's physics: the pivot diameter and the loading arm) add theirs
#: (:func:`core_values`, :func:`bolt_core_checks`)
BOLT_CORE_VALUES = ()
_DECLARED_CORE_VALUES = {"bushing": BUSHING_CORE_VALUES, "axial": AXIAL_CORE_VALUES, "spring": SPRING_KEY_VALUES,
                         "bolt": BOLT_CORE_VALUES}


def core_values(group: str, core) -> tuple:
    """What group ``group`` reads of its core row: its function's declared inputs (:data:`BUSHING_CORE_VALUES`,
    :data:`AXIAL_CORE_VALUES`, :data:`SPRING_KEY_VALUES`, :data:`BOLT_CORE_VALUES`), then every value of the core
    (``core``: a core group's values, or their names) a registered check of the group reads through its physics
    function's parameters (:func:`~synth.design.constraints.physics_inputs`), registry order.

    Derived from the registry as it is now, never kept by hand: the searches that evaluate a group once per
    distinct value of what it reads of the core (:class:`synth.optimise.batch.Batch`, the platform producer, the
    design space's product) key it on this, and the group functions hand these values to the physics
    (:func:`add_physics`). A check of the axial group whose physics reads ``pivot_diameter_mm`` makes the pivot
    diameter part of the axial group's key, with no other edit.

    >>> core_values("bolt", {"pivot_diameter_mm": 0, "loading_arm_mm": 0, "bearing_width_mm": 0})
    ('pivot_diameter_mm', 'loading_arm_mm')
    """
    out = list(_DECLARED_CORE_VALUES[group])
    for c in by_group(group):
        for k in physics_inputs(c):
            if k in core and k not in out:
                out.append(k)
    return tuple(out)


def read_core(group: str, cg: "Group", r) -> dict:
    """The core values group ``group`` reads (:func:`core_values`) at core rows ``r`` of core group ``cg``."""
    return {k: cg.values[k][r] for k in core_values(group, cg.values)}
