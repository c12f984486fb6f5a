"""``synth design INPUT``: the optimal catalog design, with every check and what binds.

Infeasible inputs get the nearest design, the constraints it violates by how
much, and the smallest input relaxations that would make it feasible. The exit
code is the verdict's (0 pass, 1 fail or infeasible, 3 incomplete), with or
without ``--json``.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field

from synth.io.outputs import json_text
from synth.design.result import FAIL
from synth.report.text import render
from synth.scenes._options import add_design_options, add_robust_options, synthesise, settings_from_args
from synth.io.documents import load_input
from synth.drive.analysis import durability_point
from synth.drive.inputs import load_drive
from synth.cad import export_result, summary_lines, require_cadquery
from synth.errors import InputError
from synth.robust.assumptions import flips
from synth import parts
from synth.cost.decision import cost_report

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("design", help="optimal tensioner from the catalogs (standardisation, cost or margin)")
    p.add_argument("input", help="design input (.yaml, .toml, .json, .xlsx; a case file works)")
    add_design_options(p)
    add_robust_options(p)
    p.add_argument("--assumptions", action="store_true",
                   help="also list the verdicts that flip inside the illustrative limits' plausible ranges "
                        "(catalogs/assumption_ranges.csv)")
    p.add_argument("--json", action="store_true", help="print the result as one JSON object (exit code as without)")
    p.add_argument("--drive", metavar="DRIVE", default=None,
                   help="the belt drive around the tensioner (.yaml, .toml, .json, .xlsx): theta_pp and f for the "
                        "wear and spring checks come from it, and the registry adds belt-slack and arm-lock checks")
    p.add_argument("--cad", metavar="DIR", default=None,
                   help="also export the 3D model of the design (STEP, STL, pictures, geometric checks) into DIR")
    p.set_defaults(func=_main)


def _main(args) -> int:
    if args.cad:  # before the work: the 3D model needs CadQuery (synth[cad])
        require_cadquery()
    d = load_input(args.input)
    note = None
    if getattr(args, "drive", None):
        d, args.drive_model, note = with_drive(d, args.drive)
    r = with_cost(d, args, synthesise)
    if note:
        r.notes.insert(0, note)
    if args.assumptions and r.parts:
        r.robust = {**r.robust, "assumptions": flips(d, r.parts, settings_from_args(args))}
    if args.json:
        print(json_text(r.to_dict(), indent=2))
    else:
        print(render(r, title=f"synth design: {args.input}"))
    cad_failed = False
    if args.cad:
        from pathlib import Path
        cad = export_cad(r, args.cad, Path(args.input).stem)
        print("\n".join(cad.lines), file=sys.stderr if args.json else sys.stdout)
        cad_failed = cad.failed
    if (r.robust.get("checks") and not r.robust.get("meets", True)) or cad_failed:
        return 1  # the capability target is missed, or a geometric check of the 3D model fails: the design fails it
    return r.exit_code


def with_cost(d, args, synthesise):
    """The synthesis of ``args`` with the design's price lines (:attr:`Result.cost`); for the cost objective also
    how much the choice depends on the prices (:func:`synth.cost.decision.cost_report`)."""
    from synth.optimise.objectives import Objective
    r = synthesise(d, args)
    cost_first = Objective.parse(args.objective).primary == "cost"
    r.cost = cost_report(d, r, sensitivity=cost_first and not r.robust, settings=settings_from_args(args))
    return r


def with_drive(d, path):
    """The design input with what the drive gives it, the drive with the design input's tensioner (arm, spring,
    calculated torque, damping target; the drive's nominal arm angle and stops kept), and a note naming each input
    taken from the drive: the arm travels from the drive's positions (nominal to installation, to the free arm),
    the differential and wrap angles of its nominal position (the hub load's direction and size), and, for a drive
    with an excitation, theta_pp and f at its durability speed. The drive returned is None when it has no
    excitation (the registry's drive checks need the response)."""
    import dataclasses

    from synth.drive.analysis import states_positions
    from synth.drive.positions import positions, travels
    from synth.drive.statics import static_state

    drive = load_drive(path)
    arm_note = ""
    if abs(drive.tensioner.arm_length_mm - d.working_arm_mm) > 0.01 * drive.tensioner.arm_length_mm:
        arm_note = (f" (the design's working arm {d.working_arm_mm:g} mm replaces the drive's arm "
                    f"{drive.tensioner.arm_length_mm:g} mm: the pulley's centre, and with it the drive, is the design's)")
    ten = {"arm_length_mm": d.working_arm_mm, "stiffness_nm_per_deg": d.spring_stiffness_nm_per_deg,
           "nominal_torque_nm": d.calculated_torque_target_nm}
    if d.damping_target_nm is not None:
        ten["friction_torque_nm"] = d.damping_target_nm
    drive = drive.with_tensioner(**ten)
    changes, taken = {}, []
    st = static_state(drive)
    wrap = float(st["wrap_deg"][drive.tensioner_index])
    changes.update(differential_angle_deg=float(st["differential_angle_deg"]), wrap_angle_deg=wrap)
    taken += [f"differential_angle_deg = {changes['differential_angle_deg']:.2f} deg and wrap_angle_deg = "
              f"{wrap:.2f} deg (hub load {st['hub_load_n'][drive.tensioner_index]:.0f} N at nominal)"]
    extra = ""
    if states_positions(drive):
        tr = travels(drive, positions(drive))
        for key, field in (("nominal_to_installation_deg", "arm_travel_nominal_to_installation_deg"),
                           ("nominal_to_free_deg", "arm_travel_nominal_to_free_deg")):
            if key in tr:
                changes[field] = tr[key]
                taken.append(f"{field} = {tr[key]:.2f} deg")
        if "working_range_deg" in tr:
            extra = (f"; the arm's working range over the belt's tolerance, wear and thermal change (shortest to worn) "
                     f"is {tr['working_range_deg']:.2f} deg (no design input takes it)")
    checks_drive = None
    if drive.dynamic:
        p = durability_point(drive)
        duration = d.durability_duration_h
        if d.durability_test == "assumed" and d.engine_type:
            arr = parts.arrays().durability
            duration = float(arr.cols["duration_h"][arr.code(d.engine_type, "engine_type")])
        changes.update(durability_test="defined", durability_theta_peak_to_peak_deg=p["theta_pp_deg"],
                       durability_frequency_hz=p["frequency_hz"], durability_duration_h=duration)
        taken.append(f"durability: theta_pp = {p['theta_pp_deg']:.3g} deg and f = {p['frequency_hz']:.3g} Hz at "
                     f"{p['speed_rpm']:g} rpm with the damping target {p['friction_nm']:g} Nm"
                     + (" (the arm locks there: theta_pp 0)" if p["locked"] else ""))
        checks_drive = drive
    d = dataclasses.replace(d, **changes)
    note = f"from the drive '{drive.name}'{arm_note}: " + "; ".join(taken) + extra
    return d, checks_drive, note


@dataclass
class CadExport:
    """What :func:`export_cad` did: the lines to print, the pictures written, whether a geometric check failed."""

    lines: list
    pictures: list = field(default_factory=list)
    failed: bool = False


def export_cad(r, out_dir, application: str | None = None, *, what: str = "--cad") -> CadExport:
    """Export the design's 3D model (thesis step 11) into ``out_dir`` (option ``what``): the summary lines, the
    pictures written (for a report that then exports no second model) and whether a geometric check failed (a
    part the CAD kernel could not build fails ``cad_solids``: exit 1, never 70).

    A failing design whose geometry cannot exist (a pulley inside its own bearing) is reported, not drawn: the
    lines say why, and the exit code stays the design's (1).
    """
    try:
        model, checks, info = export_result(r, out_dir, application=application, what=what)
    except InputError as exc:
        if not r.failed() or not any(p.field.startswith("inputs.") for p in exc.problems):
            raise
        return CadExport(["3D model not drawn (the design fails, and its geometry cannot be built): "
                          + "; ".join(str(p) for p in exc.problems)], [], True)
    lines = [f"3D model written to {out_dir}"] + summary_lines(model, checks, info)
    return CadExport(lines, [str(f) for f in info["files"] if str(f).endswith(".png")],
                     any(c.verdict == FAIL for c in checks))
