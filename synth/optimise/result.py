"""The result every solver returns, and the verification of one chosen design.

:class:`DesignResult` holds the chosen parts, the derived quantities, every
margin, the binding constraints, the objective values and the solver's
statistics. :func:`verify` re-evaluates one design from scratch (all
constraints, the chosen fidelity) with the same physics the flowchart uses;
it is how every solver's answer is checked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from synth import catalog
from synth.flowchart import PART_KEYS  # one list of part keys: the flowchart's fixed-parts mode and every solver
from synth.optimise.evaluate import CONSTRAINTS, FEAS_TOL, evaluate
from synth.optimise.space import PART_COLUMNS, SUBSYSTEMS, DesignSpace, build_space

__all__ = ["DesignResult", "Verification", "verify", "parts_of", "objective_values"]

def _plain(v):
    if isinstance(v, np.ndarray):
        v = v.reshape(-1)[0] if v.size else None
    if isinstance(v, np.generic):
        v = v.item()
    if isinstance(v, float) and not math.isfinite(v):
        return None if math.isnan(v) else ("inf" if v > 0 else "-inf")
    return v


def parts_of(sp: DesignSpace, core: int, options: dict) -> dict:
    """The part keys of core row ``core`` and subsystem option rows ``options`` of ``sp``."""
    out = {k: _plain(sp.cores.iloc[core][k]) for k in PART_COLUMNS["core"]}
    for s in SUBSYSTEMS:
        row = sp.subsystems[s].iloc[options[s]]
        for k in PART_COLUMNS[s]:
            out[k] = _plain(row[k])
    return {k: out.get(k) for k in PART_KEYS}


@dataclass
class Verification:
    """All margins and derived values of one design, evaluated alone."""

    parts: dict
    margins: dict
    values: dict
    available: bool
    fidelity: str

    @property
    def passes(self) -> bool:
        return self.available and all(m >= -FEAS_TOL for m in self.margins.values())

    def failed(self) -> dict:
        return {k: m for k, m in self.margins.items() if m < -FEAS_TOL}


def verify(d, parts: dict, *, fidelity: str = "screening", friction_circle: bool = True) -> Verification:
    """Evaluate the design ``parts`` of input ``d`` alone: every constraint, its derived values.

    >>> from synth.schema import load_input

    >>> from synth.data import case_path
    >>> v = verify(load_input(case_path("case3")), {"bearing": "6006", "pivot_class_mm": 19.0,
    ...     "supplier": "B", "damper_pad": "none", "bushing_length_mm": 20.0, "endcap_spacer": "none",
    ...     "cone_aspect_ratio": 0.0, "spring_material": "VDSiCr", "spring_wire": "R2.30",
    ...     "spring_mbd_mm": 44.0, "bolt_format": "M8x1.25", "bolt_property_class": "8.8"})
    >>> v.available, round(v.values["pivot_diameter_mm"], 1)
    (True, 20.0)
    """
    sp = build_space(d, fidelity=fidelity, friction_circle=friction_circle).restrict(parts)
    sizes = [sp.n_cores] + [len(t) for t in sp.subsystems.values()]
    if min(sizes) != 1:
        raise ValueError(f"parts do not name exactly one design: {sizes} rows match")
    ev = evaluate(sp, prune=False, keep_values=True)
    margins = {n: float(ev.core_margin_array[0, j]) for j, n in enumerate(ev.core_names)}
    available = bool(ev.core_available[0])
    values = {k: _plain(np.asarray(v)) for k, v in ev.core_values.items() if k not in ("row",)}
    values.update({k: _plain(sp.cores.iloc[0][k]) for k in ("pivot_diameter_mm", "bushing_thickness_mm")})
    for s, sub in ev.subs.items():
        available &= bool(sub.available[0, 0])
        margins.update({n: float(sub.margins[0, 0, j]) for j, n in enumerate(sub.names)})
        values.update({k: _plain(np.asarray(v)[0, 0] if np.ndim(v) >= 2 else np.asarray(v)) for k, v in sub.values.items()})
    values["main_spring_active_coils_free"] = _plain(sp.subsystems["spring"].iloc[0]["active_coils"])
    values.update(_geometry(sp))
    return Verification(dict(parts), margins, values, available, fidelity)


def _geometry(sp: DesignSpace) -> dict:
    """Dimensions of the chosen parts under the flowchart's value names (for reports and the CAD export).

    Copied from the catalog rows of the (single-design) space ``sp``; nothing is computed.
    """
    c, f = sp.cores.iloc[0], sp.fixed
    bush, ax, spr, bolt = (sp.subsystems[s].iloc[0] for s in ("bushing", "axial", "spring", "bolt"))
    rnd = bool(spr["round_wire"])
    g = {"architecture": "rotary_standard" if f["layout"] == "standard" else "rotary_reverse",
         "pulley_type": sp.inputs.pulley_shell_type, "pulley_width_mm": f["pulley_width_mm"],
         "ball_bearing": c["bearing"], "bearing_inner_diameter_mm": c["bearing_d_mm"],
         "bearing_outer_diameter_mm": c["bearing_D_mm"], "bearing_width_mm": c["bearing_B_mm"],
         "pivot_class_diameter_mm": c["pivot_class_mm"], "pivot_bushing_radial_thickness_mm": c["bushing_thickness_mm"],
         "pivot_bushing_length_mm": bush["bushing_length_mm"],
         "main_spring_material": spr["spring_material"], "main_spring_wire_section": "round" if rnd else "rectangular",
         "main_spring_wire_size_mm": [float(spr["b_mm"])] if rnd else [float(spr["b_mm"]), float(spr["h_mm"])],
         "main_spring_mean_body_diameter_mm": spr["spring_mbd_mm"],
         "bolt_format": bolt["bolt_format"], "pivot_bolt_hole_diameter_mm": bolt["pivot_bore_min_mm"]}
    if c["damper_pad"] != "none":
        g.update({"damper_pad_class": c["damper_pad"], "damper_pad_outer_diameter_mm": c["dp_outer_diameter_mm"],
                  "damper_pad_axial_height_mm": c["dp_height_mm"], "damper_pad_mean_radius_mm": c["dp_mean_radius_mm"],
                  "damper_pad_contact_area_mm2": c["dp_contact_area_mm2"]})
    if ax["endcap_spacer"] != "none":
        g.update({"endcap_spacer_class": ax["endcap_spacer"], "endcap_spacer_axial_height_mm": ax["es_height_mm"],
                  "endcap_spacer_mean_radius_mm": ax["es_mean_radius_mm"],
                  "endcap_spacer_contact_area_mm2": ax["es_contact_area_mm2"]})
    return {k: v if isinstance(v, list) else _plain(v) for k, v in g.items()}


def objective_values(sp: DesignSpace, core: int, options: dict, margin: float) -> dict:
    """``{standard, cost, margin}`` of a design given by row indices."""
    cost = float(sp.cores.iloc[core]["cost_eur"]) + sum(float(sp.subsystems[s].iloc[options[s]]["cost_eur"]) for s in SUBSYSTEMS)
    std = float(sp.cores.iloc[core]["nonstandard"]) + sum(float(sp.subsystems[s].iloc[options[s]]["nonstandard"]) for s in SUBSYSTEMS)
    return {"standard": std, "cost": round(cost, 6), "margin": margin}


def design_margin(margins: dict, axial_present: bool) -> float:
    """The margin objective of a verified design (constraints met by construction left out)."""
    vals = [m for n, m in margins.items() if CONSTRAINTS[n][3]
            and not (axial_present and n in ("damping_upper", "damping_lower"))]
    return float(min(vals)) if vals else math.inf


@dataclass
class DesignResult:
    """What every solver returns.

    ``status``: ``optimal`` (proved), ``feasible`` (an anytime solver's best),
    ``infeasible`` (then ``diagnosis`` says why and what to relax) or
    ``baseline`` (the thesis flowchart's greedy design).
    """

    status: str
    solver: str
    objective: str
    parts: dict = field(default_factory=dict)
    derived: dict = field(default_factory=dict)
    margins: dict = field(default_factory=dict)
    binding: list = field(default_factory=list)
    objectives: dict = field(default_factory=dict)
    stats: dict = field(default_factory=dict)
    diagnosis: dict | None = None
    notes: list = field(default_factory=list)
    inputs: dict | None = None  # the DesignInput as plain values, so a saved result is self-contained

    @property
    def feasible(self) -> bool:
        return self.status in ("optimal", "feasible", "baseline") and all(
            m >= -FEAS_TOL for m in self.margins.values())

    def to_dict(self) -> dict:
        return {
            "status": self.status, "solver": self.solver, "objective": self.objective,
            "parts": {k: _plain(v) for k, v in self.parts.items()},
            "objectives": {k: _plain(v) for k, v in self.objectives.items()},
            "margins": {k: _plain(v) for k, v in self.margins.items()},
            "binding": self.binding,
            "derived": {k: _plain(v) for k, v in self.derived.items()},
            "stats": {k: _plain(v) for k, v in self.stats.items()},
            "diagnosis": self.diagnosis, "notes": list(self.notes),
            "inputs": self.inputs,
        }

    def binding_table(self, n: int = 8) -> str:
        """Markdown table of the ``n`` smallest margins (what binds)."""
        rows = sorted(self.margins.items(), key=lambda kv: kv[1])[:n]
        lines = ["| constraint | step | equation | margin |", "|---|---|---|---|"]
        for name, m in rows:
            step, label, eq, _ = CONSTRAINTS[name]
            lines.append(f"| {label} | {step} | {eq} | {m:+.4f} |")
        return "\n".join(lines)


def binding_of(margins: dict, axial_present: bool) -> list:
    """Constraints whose margin is within ``optimise_binding_tolerance`` of the design's smallest margin."""
    tol = catalog.constant("optimise_binding_tolerance")
    m0 = design_margin(margins, axial_present)
    out = []
    for name, m in sorted(margins.items(), key=lambda kv: kv[1]):
        if m <= m0 + tol and CONSTRAINTS[name][3]:
            step, label, eq, _ = CONSTRAINTS[name]
            out.append({"constraint": name, "label": label, "step": step, "equation": eq, "margin": m})
    return out


def _inputs_of(d) -> dict | None:
    """The design input as a dict of plain values (``None`` if it is not a dataclass)."""
    import dataclasses
    if not dataclasses.is_dataclass(d):
        return None
    return {k: _plain(v) for k, v in dataclasses.asdict(d).items()}


def build_result(sp: DesignSpace, core: int, options: dict, *, status: str, solver: str, objective: str,
                 stats: dict, notes: list | None = None) -> DesignResult:
    """Verify the design of row indices ``core``/``options`` and wrap it in a :class:`DesignResult`."""
    parts = parts_of(sp, core, options)
    v = verify(sp.inputs, parts, fidelity=sp.fidelity, friction_circle=sp.friction_circle)
    ax = bool(v.values.get("axial_damping_present"))
    margin = design_margin(v.margins, ax)
    res = DesignResult(status=status, solver=solver, objective=objective, parts=parts, derived=v.values,
                       margins=v.margins, binding=binding_of(v.margins, ax),
                       objectives=objective_values(sp, core, options, margin), stats=dict(stats),
                       notes=list(notes or []) + list(sp.notes), inputs=_inputs_of(sp.inputs))
    if not v.passes and status != "baseline":
        res.notes.append("verification failed: " + ", ".join(f"{k} {m:+.3g}" for k, m in v.failed().items()))
    return res
