"""``synth drive DRIVE``: the belt drive around the tensioner.

Prints the static span tensions and hub loads, the natural frequencies (arm
free and arm locked), the periodic response over the engine-speed sweep (the
arm's peak-to-peak angle, the lowest span tension, the critical friction
torque), theta_pp and f at the durability speed, whether the belt goes slack
or the arm locks there, and the tolerance check of the periodic solution.

Exit codes: 0 the belt stays taut and the arm swings at the durability
speed, 1 otherwise (or the periodic solution moved more than its tolerance),
2 invalid input.
"""

from __future__ import annotations
from synth.errors import InputError, Problem
from synth.io.outputs import write_figure, json_text


__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("drive", help="the belt drive around the tensioner: tensions, modes, arm response vs speed")
    p.add_argument("input", metavar="DRIVE", help="drive file (.yaml, .toml, .json, or a workbook with a Drive sheet)")
    p.add_argument("--json", action="store_true", help="print the analysis as one JSON object")
    p.add_argument("--friction", type=float, default=None, metavar="NM",
                   help="the tensioner's friction torque (damping) instead of the file's [Nm]")
    p.add_argument("--plot", metavar="FILE", help="save arm amplitude and span tension against speed (PNG, SVG, PDF)")
    p.set_defaults(func=_main)


def _main(args) -> int:
    from synth.drive.analysis import analyse
    from synth.drive.inputs import load_drive
    from synth.scenes.shrink_fit import plot_path
    plot_path(args.plot)
    drive = load_drive(args.input)
    if args.friction is not None:
        if not 0.0 <= args.friction <= 100.0:
            raise InputError(Problem("--friction", args.friction, "a friction torque in [0, 100] Nm"))
        drive = drive.with_tensioner(friction_torque_nm=float(args.friction))
    res = analyse(drive)
    locked = bool(res.get("durability", {}).get("locked", False))
    ok = not res["slack"]["slack"] and not locked and res["solver"].get("within_tolerance", True)
    if args.plot:
        from synth.report.plots import drive_figure
        write_figure(drive_figure(res), args.plot, "--plot", dpi=120)
    if args.json:
        print(json_text({**res, "verdict": "pass" if ok else "fail"}, indent=2))
    else:
        print(format_report(res))
        if args.plot:
            print(f"plot saved to {args.plot}")
    return 0 if ok else 1


def format_report(res: dict) -> str:
    """The text report of :func:`synth.drive.analysis.analyse`."""
    st = res["static"]
    lines = [f"synth drive: {res['name']}", "", "Static state (effective tensions, centrifugal tension excluded)",
             f"  tensioner tension {st['tensioner_tension_n']:.1f} N, take-up {st['take_up_mm_per_rad']:.3f} mm/rad, "
             f"differential angle {st['differential_angle_deg']:.1f} deg",
             f"  {'span':<14}{'length [mm]':>12}{'tension [N]':>13}"]
    for name, length, t in zip(res["spans"], st["span_length_mm"], st["tension_n"]):
        lines.append(f"  {name:<14}{length:>12.1f}{t:>13.1f}")
    lines.append(f"  {'pulley':<14}{'wrap [deg]':>12}{'hub load [N]':>13}{'load [Nm]':>11}")
    for name, w, h, q in zip(res["pulleys"], st["wrap_deg"], st["hub_load_n"], st["load_torque_nm"]):
        lines.append(f"  {name:<14}{w:>12.1f}{h:>13.1f}{q:>11.2f}")
    m = res["modes"]
    lines += ["", "Natural frequencies [Hz]",
              "  arm free:   " + ", ".join(f"{f:.1f}" for f in m["arm_free_hz"]),
              "  arm locked: " + ", ".join(f"{f:.1f}" for f in m["arm_locked_hz"]), "",
              f"Periodic response (friction {res['friction_nm']:g} Nm; harmonic balance, {res['solver']['harmonics']} "
              f"harmonics, regularisation {res['solver']['regularisation']:g})",
              f"  {'speed [rpm]':>11}{'theta_pp [deg]':>15}{'f [Hz]':>9}{'min tension [N]':>16}{'crit. friction [Nm]':>20}"]
    sw = res["sweep"]
    for i, s in enumerate(sw["speed_rpm"]):
        lines.append(f"  {s:>11.0f}{sw['theta_pp_deg'][i]:>15.3f}{sw['arm_frequency_hz'][i]:>9.1f}"
                     f"{min(sw['tension_min_n'][i]):>16.1f}{sw['critical_friction_nm'][i]:>20.3f}"
                     + ("  locked" if sw["locked"][i] else ""))
    sl = res["slack"]
    lines += ["", f"Belt: {'SLACK' if sl['slack'] else 'taut'} (lowest effective tension {sl['min_tension_n']:.1f} N in "
              f"span {sl['span']} at {sl['at_speed_rpm']:.0f} rpm; limit {sl['limit_n']:g} N)"]
    if "durability" in res:
        d = res["durability"]
        lines.append(f"Durability speed {d['speed_rpm']:g} rpm: theta_pp = {d['theta_pp_deg']:.3f} deg, f = "
                     f"{d['frequency_hz']:.2f} Hz; the arm {'LOCKS' if d['locked'] else 'swings'} (friction "
                     f"{d['friction_nm']:g} Nm, critical {d['critical_friction_nm']:.3f} Nm)")
    sv = res["solver"]
    if "change" in sv:
        lines.append(f"Tolerance check (regularisation halved, harmonics doubled): theta_pp moved "
                     f"{100 * sv['change']['theta_pp']:.2f} %, lowest tension {100 * sv['change']['tension_min']:.2f} % "
                     f"(tolerance {100 * sv['tolerance']:g} %): {'within' if sv['within_tolerance'] else 'OUTSIDE'}")
    if "slip" in res:
        for name, margins in res["slip"].items():
            lines.append(f"Slip margin on {name}: lowest {min(margins):+.3f} (Euler-Eytelwein)")
    return "\n".join(lines)
