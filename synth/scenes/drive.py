"""``synth drive DRIVE``: the belt drive around the tensioner.

Prints the static span tensions and hub loads; the tensioner's positions
(free arm, worn, longest, nominal, shortest and installation belt: the arm
angle, pulley centre, arm-to-hub-load angle, hub load and its direction,
tension, wrap, drive and required belt length) and the duty table (span
tensions and hub loads per engine speed) in a drive report's shape, when the
drive states them; the natural frequencies (arm free and locked; the free
system's with the crank's inertia, and over the EA range); and, for a drive
with an excitation, the periodic response over the engine-speed sweep,
theta_pp and f at the durability speed, belt slack, arm lock and the
tolerance check. ``--layout FILE`` draws the layout with the arm at each
position.

Exit codes: 0 every position within the arm's stops, every span taut, and (with
an excitation) the belt taut and the arm swinging at the durability speed with
the periodic solution within its tolerance; 1 otherwise; 2 invalid input.
"""

from __future__ import annotations
from synth.errors import InputError, Problem
from synth.io.outputs import figure_path, json_text, write_figure


__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("drive", help="the belt drive around the tensioner: tensions, modes, arm response vs speed")
    p.add_argument("input", metavar="DRIVE", help="drive file (.yaml, .toml, .json, or a workbook with a Drive sheet)")
    p.add_argument("--json", action="store_true", help="print the analysis as one JSON object")
    p.add_argument("--friction", type=float, default=None, metavar="NM",
                   help="the tensioner's friction torque (damping) instead of the file's [Nm]")
    p.add_argument("--plot", metavar="FILE", help="save arm amplitude and span tension against speed (PNG, SVG, PDF; "
                                                   "a drive with an excitation)")
    p.add_argument("--layout", metavar="FILE", help="save the layout: pulleys, spans, the arm at each position "
                                                     "(PNG, SVG, PDF)")
    p.set_defaults(func=_main)


def _main(args) -> int:
    from synth.drive.analysis import analyse
    from synth.drive.inputs import load_drive
    figure_path(args.plot, "--plot")
    figure_path(args.layout, "--layout")
    drive = load_drive(args.input)
    if args.friction is not None:
        if not 0.0 <= args.friction <= 100.0:
            raise InputError(Problem("--friction", args.friction, "a friction torque in [0, 100] Nm"))
        drive = drive.with_tensioner(friction_torque_nm=float(args.friction))
    if args.plot and not drive.dynamic:
        raise InputError(Problem("--plot", args.plot, "a drive with an excitation (the plot is the response against "
                                                      "speed; --layout draws the layout)"))
    res = analyse(drive)
    ok = not res["problems"]
    if args.plot:
        from synth.report.plots import drive_figure
        write_figure(drive_figure(res), args.plot, "--plot", dpi=120)
    if args.layout:
        from synth.scenes.drive_layout import layout_figure
        write_figure(layout_figure(drive, res), args.layout, "--layout", dpi=120)
    if args.json:
        print(json_text({**res, "verdict": "pass" if ok else "fail"}, indent=2))
    else:
        print(format_report(res))
        for what, path in (("plot", args.plot), ("layout", args.layout)):
            if path:
                print(f"{what} saved to {path}")
        print("\nVerdict: " + ("PASS (no finding)" if ok else f"FAIL ({'; '.join(res['problems'])})"))
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
    if "positions" in res:
        lines += [""] + position_lines(res)
    if "duty" in res:
        lines += [""] + duty_lines(res["duty"])
    if "modes" in res:
        m = res["modes"]
        lines += ["", "Natural frequencies [Hz] (the crank's motion given)",
                  "  arm free:   " + ", ".join(f"{f:.1f}" for f in m["arm_free_hz"]),
                  "  arm locked: " + ", ".join(f"{f:.1f}" for f in m["arm_locked_hz"])]
        if "system" in m:
            sy = m["system"]
            text = "  free system (crank free with its inertia): " + ", ".join(f"{f:.2f}" for f in sy["frequency_hz"])
            if "range" in sy:
                (lo, hi), (f_lo, f_hi) = sy["range"]["ea_per_rib_n"], sy["range"]["frequency_hz"]
                text += (f" with EA {sy['ea_per_rib_n']:.0f} N per rib; the first moves {f_lo[0]:.2f}-{f_hi[0]:.2f} "
                         f"over EA {lo:.0f}-{hi:.0f} N per rib (synth.drive.belt)")
            lines.append(text)
    if "sweep" in res:
        lines += [""] + _response_lines(res)
    lines += [""] + ([f"Findings: {'; '.join(res['problems'])}"] if res["problems"] else ["Findings: none"])
    return "\n".join(lines)


_ROWS = (("from free arm [deg]", "from_free_arm_deg", ".1f"), ("arm angle [deg]", "arm_angle_deg", ".1f"),
         ("pulley x [mm]", "centre_x_mm", ".1f"), ("pulley y [mm]", "centre_y_mm", ".1f"),
         ("arm to hub load [deg]", "beta_deg", ".1f"), ("hub load direction [deg]", "hub_direction_deg", ".1f"),
         ("hub load [N]", "hub_load_n", ".1f"), ("tension [N]", "tension_n", ".1f"), ("wrap [deg]", "wrap_deg", ".1f"),
         ("drive length [mm]", "drive_length_mm", ".1f"), ("required belt length [mm]", "required_belt_length_mm", ".1f"),
         ("spring torque [Nm]", "spring_torque_nm", ".2f"))


def position_lines(res: dict) -> list[str]:
    """The tensioner table in a drive report's shape: one column per position, one row per quantity."""
    from synth.drive.positions import POSITION_NAMES
    pos = res["positions"]
    rows = pos["rows"]
    w = 13
    out = ["Tensioner positions (angles counter-clockwise from +x; the report's names in the first row)",
           f"  {'':<26}" + "".join(f"{POSITION_NAMES[r['position']]:>{w}}" for r in rows),
           f"  {'belt':<26}" + "".join(f"{r['position']:>{w}}" for r in rows)]
    for label, key, fmt in _ROWS:
        cells = []
        for r in rows:
            v = r.get(key)
            cells.append(f"{v:>{w}{fmt}}" if r["found"] and v is not None else f"{'-':>{w}}")
        if any(c.strip() != "-" for c in cells):
            out.append(f"  {label:<26}" + "".join(cells))
    for r in rows:
        if not r["found"]:
            out.append(f"  {r['position']}: the belt is {r['beyond_mm']:.2f} mm beyond what the arm takes up before "
                       f"its {r.get('stop', '')} stop")
    tr = res.get("travels", {})
    if tr:
        out.append("  travels: " + ", ".join(f"{k.replace('_deg', '').replace('_', ' ')} {v:.1f} deg"
                                            for k, v in tr.items()))
    if pos.get("elongation_mm") is not None:
        out.append(f"  belt {pos['belt_length_mm']:.1f} mm; its elongation at the nominal tension "
                   f"{pos['elongation_mm']:.2f} mm (required belt length = drive length - elongation)")
    return out


def duty_lines(duty: dict) -> list[str]:
    """The duty table in a drive report's shape: per duty point, each span's tension and each pulley's hub load."""
    w = 10
    names, spans = duty["pulleys"], duty["spans"]
    head = f"  {'speed [rpm]':>11}{'time [%]':>9}"
    out = ["Duty cycle, the arm at nominal: span tension [N] (each span named by the pulleys it joins, in the "
           "belt's travel)", head + "".join(f"{s:>{w + 4}}" for s in spans)]
    for k, speed in enumerate(duty["speed_rpm"]):
        time = duty["time_pct"][k]
        out.append(f"  {speed:>11.0f}{'' if time is None or time != time else format(time, '.1f'):>9}"
                   + "".join(f"{t:>{w + 4}.0f}" for t in duty["tension_n"][k]))
    out += ["Hub load [N]", head + "".join(f"{n:>{w}}" for n in names)]
    for k, speed in enumerate(duty["speed_rpm"]):
        time = duty["time_pct"][k]
        out.append(f"  {speed:>11.0f}{'' if time is None or time != time else format(time, '.1f'):>9}"
                   + "".join(f"{h:>{w}.0f}" for h in duty["hub_load_n"][k]))
    return out


def _response_lines(res: dict) -> list[str]:
    lines = [f"Periodic response (friction {res['friction_nm']:g} Nm; harmonic balance, {res['solver']['harmonics']} "
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
    return lines
