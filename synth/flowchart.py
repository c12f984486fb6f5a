"""The thesis design flowchart (steps 0-10): its order and its selection loops, numbers from the evaluator.

:func:`run` walks the thesis's sequential procedure: Table 1 bearing, Table 2
pivot class, damping split, "lengthen the bushing", damper-pad and endcap-spacer
classes from the axial damping (Tables 3-4; the next class of each element
while the end-of-life damping fails), the automatic spring search (a round
wire where one passes, else rectangular), the bolt escalation (class first,
then format). Each rule and the sentence of the thesis it comes from are listed
in ``docs/sections/flowchart_rules.md``. Every number it compares comes from
:mod:`synth.design.evaluate` (the one evaluator the optimiser and the bulk
engine use), and the design it ends with is verified by
:func:`synth.design.verify.verify`: its checks are the registry's.

``run(d, parts=...)`` verifies a given design (an optimiser's, a saved
result's) through the same evaluator instead of selecting one.

>>> from synth.scenes.demo import default_input
>>> r = run(default_input())
>>> r.parts["ball_bearing"], r.values["architecture"]
('6006', 'rotary_standard')
"""

from __future__ import annotations

import numpy as np

from synth import catalog

from synth.parts import arrays, next_catalog_length_mm
from synth.design.assessment import passes
from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.constraints import TENSIONER_GROUPS
from synth.design.rules import echo
from synth.design.settings import DEFAULT
from synth.schema import plausibility
from synth.design.result import NOT_VERIFIED, Check, Result, checks_of, plain
from synth.design.space import (PART_DEFAULTS, PART_KEYS, axial_attributes, bolt_attributes, bushing_attributes,
                                core_attributes, space, spring_attributes)
from synth.design.verify import evaluate_design, inputs_of, values_of, verify
from synth.model import ball_bearing, damping, pivot
from synth.errors import InputError, Problem
from synth.design.constraints import REGISTRY
from synth.design.verify import parts_of_attributes

__all__ = ["Settings", "run", "STEP_NAMES", "PART_KEYS"]

Settings = evaluate.Settings

STEP_NAMES = {
    0: "Execution selection", 1: "Ball bearing", 2: "Pivot diameter", 3: "Damping", 4: "Pivot bushing",
    5: "Plastic element wear", 6: "Axial stack-up", 7: "Packaging", 8: "Cone spring", 9: "Main spring",
    10: "Tilting, sliding and bolt",
}

_ONE = np.zeros(1, dtype=np.int64)


class _Stop(Exception):
    """The thesis procedure cannot continue (no Table 2 class, a self-locking arm)."""

    def __init__(self, step: int, why: str, groups: dict):
        super().__init__(why)
        self.step, self.why, self.groups = step, why, groups


class _Walk:
    """The state of one run of the procedure: the application, the choices so far, notes and steps run."""

    def __init__(self, d, settings: Settings):
        self.d, self.s = d, settings
        self.apps = Applications.of([d])
        self.p = arrays()
        self.notes: list = []
        self.steps: list = [0]
        self.required: dict = {}

    # --- steps 1-3 ---------------------------------------------------------------------------------------
    def core_group(self, bearing: int, cls: float, supplier: int, pad: int):
        attrs = core_attributes(self.p, [bearing], [cls], [supplier], [pad])
        return attrs, evaluate.core(self.apps, _ONE, attrs, self.s, detail=True)

    def step1_3(self):
        d, p = self.d, self.p
        hl = float(self.apps.hubload_nominal_n[0])
        self.steps.append(1)
        bearing = p.bearing.code(str(ball_bearing.select_bearing(hl, d.engine_fuel)[0]))
        self.steps.append(2)
        if d.pivot_bushing_radial_thickness_mm is None:
            supplier = int(np.argmax(p.bushing.radial_thickness_mm))
            self.notes.append(f"pivot bushing radial thickness not given: {p.bushing.radial_thickness_mm[supplier]:g} mm "
                              f"assumed (supplier {p.bushing.key[supplier]}, the thickest wall of the catalog)")
        else:
            supplier = int(np.flatnonzero(np.isclose(p.bushing.radial_thickness_mm,
                                                     float(d.pivot_bushing_radial_thickness_mm)))[0])
        arms, classes, _ = p.table2[bearing]
        column, in_table = pivot.table2_column(arms, float(d.working_arm_mm)) if len(arms) else (0, False)
        std = float(classes[column]) if len(arms) else float(d.pivot_class_diameter_mm or 0.0)
        cls = std if d.pivot_class_diameter_mm is None else float(d.pivot_class_diameter_mm)
        if d.pivot_class_diameter_mm is None:
            self.notes.append(f"pivot class: Table 2 standard {std:g} mm (bearing {p.bearing.key[bearing]}, working arm "
                              f"{d.working_arm_mm:g} mm)")
        elif cls > std:
            self.notes.append(f"pivot class {cls:g} mm is custom and above Table 2's standard {std:g} mm (step 2 allows "
                              "only smaller custom values); the arm-wall check, the reason for that limit, decides")
        attrs, cg = self.core_group(bearing, cls, supplier, -1)
        if not in_table:
            raise _Stop(2, f"step 2 has no Table 2 pivot class for bearing {p.bearing.key[bearing]} and working arm "
                           f"{d.working_arm_mm:g} mm; later steps are not run", {"core": cg})
        self.steps.append(3)
        if not passes(cg.margins["self_locking"][0]):
            raise _Stop(3, "the arm self-locks: the friction circle exceeds the lever; later steps are not run",
                        {"core": cg})
        pad = -1
        if cg.values["axial_damping_present"][0] > 0:
            # Tables 3-4 are entered with the axial damping of eq. (9) itself (both friction faces)
            dax = float(cg.values["axial_damping_nm"][0])
            row, within = damping.axial_group_class(dax, p.damper_pad.max_axial_damping_nm)
            pad = int(row)
            if not within:
                self.notes.append(f"axial damping {dax:.3g} Nm above every damper-pad class of Table 3: the largest "
                                  "is checked")
            attrs, cg = self.core_group(bearing, cls, supplier, pad)
        return attrs, cg

    # --- step 4 ------------------------------------------------------------------------------------------------
    def step4(self, cg) -> dict:
        p, sup = self.p, int(cg.values["supplier_code"][0])
        lengths = p.bushing_lengths[sup]
        self.steps.append(4)
        if not self.apps.met("durability")[0]:
            self.notes.append("step 4: durability test missing, the bushing length cannot be sized; the shortest "
                              "catalog length that fits is taken and its wear checks are not verified")
            g = evaluate.bushing(self.apps, cg, np.zeros(len(lengths), int),
                          bushing_attributes(p, np.full(len(lengths), sup), lengths), self.s)
            fits = np.flatnonzero(passes(g.margins["bushing_length"]))
            return bushing_attributes(p, [sup], [lengths[fits[0] if len(fits) else 0]])
        if self.s.bushing_length_scheme == "thesis":
            start, step = catalog.constant("bush_length_ratio_start"), catalog.constant("bush_length_ratio_step")
            d_p = float(cg.values["pivot_diameter_mm"][0])
            l_max = float(evaluate.bushing(self.apps, cg, _ONE, bushing_attributes(p, [sup], [d_p]), self.s)
                          .values["pivot_bushing_length_max_mm"][0])
            count = int(np.clip(np.ceil((l_max / d_p - start) / step) + 1, 1, 64))  # bounded, whatever the input
            cand = (start + step * np.arange(count)) * d_p
        else:
            cand = lengths
        g = evaluate.bushing(self.apps, cg, np.zeros(len(cand), int), bushing_attributes(p, np.full(len(cand), sup), cand),
                      self.s)
        ok = g.ok()
        fits = passes(g.margins["bushing_length"])
        if ok.any():
            i = int(np.argmax(ok))
        else:
            i = int(np.flatnonzero(fits)[-1]) if fits.any() else 0
            self.notes.append("no bushing length passes every step 4 check: the thesis's next move is a larger pivot "
                              "diameter")
        length = float(cand[i])
        part = float(next_catalog_length_mm(length, lengths))
        self.required["pivot_bushing_length_required_mm"] = length
        if part != length:
            self.notes.append(f"pivot bushing: {length:g} mm required; the next catalog length of supplier "
                              f"{p.bushing.key[sup]} is {part:g} mm (the part)")
        return bushing_attributes(p, [sup], [part])

    # --- steps 5, 6, 8 (the axial damping group) ---------------------------------------------------------------
    def step5_8(self, attrs_core, cg) -> tuple[dict, dict, object]:
        p = self.p
        pad = int(attrs_core["pad_code"][0])
        if pad < 0:
            self.notes.append("no axial damping: steps 5 (plastic wear), 6 (stack-up) and 8 (cone spring) are not "
                              "needed")
            return attrs_core, axial_attributes(p, [-1], [0.0], [0.0], [0.0]), cg
        self.steps += [5, 6, 8]
        zeta = catalog.constant("cone_spring_default_aspect_ratio")
        phi = catalog.constant("cone_spring_nominal_deflection_ratio")
        dax = float(cg.values["axial_damping_nm"][0])
        spacer = int(damping.axial_group_class(dax, p.endcap_spacer.max_axial_damping_nm)[0])
        self.notes.append(f"plastic elements initialised from Tables 3-4 at the axial damping {dax:.3g} Nm: damper pad "
                          f"{p.damper_pad.key[pad]}, endcap spacer {p.endcap_spacer.key[spacer]}")
        attempt = 1
        while True:
            ax = axial_attributes(p, [spacer], [zeta], [phi], [0.0])
            g = evaluate.axial(self.apps, cg, _ONE, ax, self.s.judge)  # the loop continues where the judge fails
            if passes(g.margins["damping_eol"][0]):
                return attrs_core, ax, cg
            # step 5: the EOL damping is below its limit: larger contact surfaces (the next class of each element
            # not yet at its largest), the cone spring resized for the same axial damping, the wear run again
            nxt_pad, nxt_spacer = _next_class(p.damper_pad, pad), _next_class(p.endcap_spacer, spacer)
            eol = f"end-of-life damping {g.values['damping_eol_nm'][0]:.3f} Nm below the limit " \
                  f"{g.values['damping_eol_limit_nm'][0]:.3g} Nm"
            if nxt_pad == pad and nxt_spacer == spacer:
                self.notes.append(f"step 5, attempt {attempt}: {eol} with the largest contact surfaces "
                                  f"({p.damper_pad.key[pad]}/{p.endcap_spacer.key[spacer]}); no larger class")
                return attrs_core, ax, cg
            self.notes.append(f"step 5, attempt {attempt}: plastic elements {p.damper_pad.key[pad]}/"
                              f"{p.endcap_spacer.key[spacer]}: {eol}; contact surfaces increased to "
                              f"{p.damper_pad.key[nxt_pad]}/{p.endcap_spacer.key[nxt_spacer]}")
            pad, spacer, attempt = nxt_pad, nxt_spacer, attempt + 1
            attrs_core, cg = self.core_group(int(attrs_core["bearing_code"][0]),
                                             float(attrs_core["pivot_class_diameter_mm"][0]),
                                             int(attrs_core["supplier_code"][0]), pad)

    # --- step 9 ------------------------------------------------------------------------------------------------
    def step9(self, cg) -> dict:
        d, p = self.d, self.p
        self.steps += [7, 9]
        if d.main_spring_mode == "manual":
            wire = _wire_code(p, d.main_spring_wire_section, d.main_spring_wire_size_mm)
            return spring_attributes(p, [p.spring_material.code(d.main_spring_material, "main_spring_material")],
                                     [wire], [float(d.main_spring_mean_body_diameter_mm)])
        step = catalog.constant("main_spring_mbd_step_mm")
        d_in, d_out = float(cg.values["spring_housing_inner_diameter_mm"][0]), \
            float(cg.values["spring_housing_outer_diameter_mm"][0])
        mbd = np.arange(np.ceil(d_in / step) * step, np.floor(d_out / step) * step + step / 2, step)
        if not len(mbd):  # no mean diameter between the housing's walls: the middle one, whose contact checks fail
            mbd = np.array([(d_in + d_out) / 2.0])
            self.notes.append(f"main spring (automatic): the spring housing's inner diameter {d_in:g} mm is not below "
                              f"its outer diameter {d_out:g} mm; no spring fits (mean diameter {mbd[0]:g} mm shown)")
        m, w, dd = (x.ravel() for x in np.meshgrid(np.arange(len(p.spring_material)), np.arange(len(p.spring_wire)),
                                                   mbd, indexing="ij"))
        opts = spring_attributes(p, m, w, dd)
        g = evaluate.spring(self.apps, evaluate.spring_keys(cg, _ONE), np.zeros(len(m), int), opts, self.s)
        ok = g.ok()
        cost = opts["cost_eur_times_stiffness"] / float(self.apps.spring_stiffness_nm_per_deg[0])
        rnd = np.asarray(opts["round_wire"], dtype=bool)
        if ok.any():
            # step 9: "Round wire is preferred due to the lower cost ... if it is not sufficient, the rectangular
            # wire is implemented": a feasible round-wire spring whenever one exists; within the section the text
            # gives no order, the cheapest (synth.cost prices at the default volume) is taken
            section = rnd if (ok & rnd).any() else ~rnd
            pool = ok & section
            order = np.lexsort((-g.values["main_spring_safety_factor"], cost, ~pool))
            i = int(order[0])
            which = "round wire suffices" if rnd[i] else "no round wire suffices: rectangular wire"
            self.notes.append(f"main spring (automatic): {int((ok & rnd).sum())} round-wire and "
                              f"{int((ok & ~rnd).sum())} rectangular-wire springs pass of {len(m)} catalog springs; "
                              f"{which} (step 9), the cheapest feasible of the section is chosen")
        else:
            i = int(np.argmax(g.min_margin(objective_only=False)))
            self.notes.append(f"main spring (automatic): none of {len(m)} catalog springs passes; the one with the "
                              "largest smallest margin is reported")
        return {k: v[[i]] for k, v in opts.items()}

    # --- step 10 -----------------------------------------------------------------------------------------------
    def step10(self, cg) -> dict:
        d, p = self.d, self.p
        self.steps.append(10)
        if d.bolt_mode == "manual":
            p.bolt.code(d.bolt_format, "bolt_format")
            return bolt_attributes(p, [p.bolt_head.code(f"{d.bolt_format} hex", "bolt_format")],
                                   [p.bolt_class.code(d.bolt_property_class, "bolt_property_class")])
        t = space().tables["bolt"]
        rows = np.flatnonzero(np.isfinite(t["escalation_order"]))
        rows = rows[np.argsort(t["escalation_order"][rows], kind="stable")]
        opts = {k: v[rows] for k, v in t.items()}
        if not self.apps.met("fixation")[0]:
            self.notes.append("step 10 not run: fixation data missing; the first bolt of the escalation is shown "
                              "and its checks are not verified")
            return {k: v[:1] for k, v in opts.items()}
        g = evaluate.bolt(self.apps, cg, np.zeros(len(rows), int), opts, self.s)
        ok = passes(g.margins["bolt_yield"])
        i = int(np.argmax(ok)) if ok.any() else len(rows) - 1
        return {k: v[[i]] for k, v in opts.items()}


def _next_class(table, row: int) -> int:
    """The Table 3/4 row after ``row`` (the next larger axial-damping bound: larger contact surfaces), or ``row``
    itself at the largest."""
    order = np.argsort(table.max_axial_damping_nm, kind="stable")
    k = int(np.flatnonzero(order == row)[0])
    return int(order[k + 1]) if k + 1 < len(order) else row


def _wire_code(p, section: str, size_mm) -> int:
    """The ``spring_wires.csv`` row of a section and size; an unknown size lists the catalog's."""
    w = p.spring_wire
    b, h = (size_mm[0], size_mm[0]) if section == "round" else (size_mm[0], size_mm[1])
    hit = np.flatnonzero((w.section == section) & np.isclose(w.b_mm, b) & np.isclose(w.h_mm, h))
    if not len(hit):
        sizes = ", ".join(f"[{bb:g}]" if section == "round" else f"[{bb:g}, {hh:g}]"
                          for bb, hh, s in zip(w.b_mm, w.h_mm, w.section) if s == section)
        raise InputError(Problem("main_spring_wire_size_mm", size_mm, f"a {section} wire of catalogs/spring_wires.csv: "
                                 + sizes))
    return int(hit[0])


def _stopped(walk: _Walk, stop: _Stop) -> Result:
    """The result of a run the procedure could not complete: the checks of what ran, the rest not verified."""
    apps, d = walk.apps, walk.d
    groups = {"input": evaluate.inputs(apps, _ONE, walk.s), **stop.groups}
    checks = checks_of(groups, apps)
    done = {c.id for c in checks}
    for cid, c in REGISTRY.items():
        if cid not in done and c.group in TENSIONER_GROUPS:
            checks.append(Check(cid, None, None, None, NOT_VERIFIED, f"not run: the flowchart stopped at step {stop.step}"))
    order = {cid: i for i, cid in enumerate(REGISTRY)}
    checks.sort(key=lambda c: order[c.id])
    values = {k: plain(float(v[0])) for k, v in groups["core"].values.items()
              if np.ndim(v) and np.asarray(v).dtype.kind == "f"}
    return Result(status="baseline", solver="flowchart", values=values, checks=checks,
                  notes=plausibility(d) + walk.notes + [stop.why] + walk.s.notes(), inputs=inputs_of(d),
                  settings=walk.s.as_dict(), steps_run=sorted(set(walk.steps)), rules=echo(walk.s.rules))


def run(design_input, settings: Settings | None = None, parts: dict | None = None, *, time_points: int = 60) -> Result:
    """Run the thesis procedure on a validated :class:`~synth.schema.DesignInput`, or verify ``parts``.

    ``parts`` (optional) fixes every catalog choice (the keys of :data:`PART_KEYS`,
    as every result reports them): the design is verified through the same
    evaluator, with nothing selected. ``time_points`` keeps that many points of
    the plastic-wear history for the report's graphs.
    """
    s = settings or DEFAULT
    if parts:
        missing = [k for k in PART_KEYS if k not in parts and k not in PART_DEFAULTS]
        if missing:
            raise InputError(Problem("parts", sorted(parts), "a dict with the keys " + ", ".join(PART_KEYS)))
        r = verify(design_input, dict(parts), s, status="verified", solver="flowchart", time_points=time_points,
                   notes=["fixed-parts verification: every catalog choice is given; the flowchart checks it and "
                          "selects nothing"])
        r.steps_run = list(range(11))
        return r
    walk = _Walk(design_input, s)
    try:
        core_attrs, cg = walk.step1_3()
    except _Stop as stop:
        return _stopped(walk, stop)
    bush = walk.step4(cg)
    core_attrs, ax, cg = walk.step5_8(core_attrs, cg)
    spr = walk.step9(cg)
    bolt = walk.step10(cg)
    attrs = {"core": core_attrs, "bushing": bush, "axial": ax, "spring": spr, "bolt": bolt}
    groups = evaluate_design(walk.apps, attrs, s, detail=True, time_points=time_points)
    values = values_of(groups, attrs)
    values.update(walk.required)
    res = Result(status="baseline", solver="flowchart", objective="thesis procedure",
                 parts=parts_of_attributes(attrs, groups),
                 values=values, checks=checks_of(groups, walk.apps),
                 notes=plausibility(design_input) + walk.notes + s.notes(), inputs=inputs_of(design_input),
                 settings=s.as_dict(), steps_run=sorted(set(walk.steps)), rules=echo(s.rules))
    if "_history" in groups["axial"].values:
        res.curves["plastic_wear"] = {k: np.asarray(v).reshape(-1).tolist()
                                      for k, v in groups["axial"].values["_history"].items()}
    return res
