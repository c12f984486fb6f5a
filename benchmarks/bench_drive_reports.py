"""Benchmark of a drive report's statics (issue 37): a ten-pulley drive, six tensioner positions, a six-point duty cycle.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_drive_reports.py [--repeat 5] [--quick]

BLAS is held to one thread (set before numpy is imported): the algebra is a few small arrays per arm angle. The
ten-pulley drive (built here: a crank, six accessories on a 340 mm circle, two backside idlers, the tensioner on
the span leaving the crank) states its tensioner by free-arm stop, preload, rate, nominal torque and installation
stop, its belt by ribs, tolerance and wear, and six duty points. Prints one markdown table, measured side by side
in one run (best of ``--repeat``, every cache cleared before each run): validating the drive (which solves the
nominal position), the six positions, the duty table, both together, and ``analyse`` (statics, positions, duty,
the free system's modes over the EA range); then the same for the four Gates report drives of the validation tests.
The target is 0.2 s for the six positions and the duty cycle.
"""

from __future__ import annotations

import os

for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def ten_pulley_drive() -> dict:
    """The benchmark's drive as a drive-file mapping (travel counter-clockwise round a 340 mm circle)."""
    angles = np.radians([270, 320, 10, 60, 120, 170, 220])
    radii = [80, 45, 60, 35, 55, 40, 50]
    names = ["CRK", "WP", "ALT", "PS", "A_C", "FAN", "AUX"]
    big = 340.0
    pts = [(round(big * np.cos(a), 1), round(big * np.sin(a), 1)) for a in angles]
    pulleys = [{"name": "CRK", "role": "crank", "x_mm": pts[0][0], "y_mm": pts[0][1], "pitch_diameter_mm": 162.4,
                "effective_diameter_mm": 160.0, "inertia_kg_m2": 0.3},
               {"name": "TEN", "role": "tensioner", "pitch_diameter_mm": 77.2, "effective_diameter_mm": 79.6,
                "backside": True, "inertia_kg_m2": 0.0004}]
    for k in range(1, 7):
        pulleys.append({"name": names[k], "role": "driven", "x_mm": pts[k][0], "y_mm": pts[k][1],
                        "pitch_diameter_mm": 2 * radii[k] + 2.4, "effective_diameter_mm": 2 * radii[k],
                        "inertia_kg_m2": 0.003})
        if k in (2, 4):
            a = (angles[k] + angles[k + 1]) / 2
            pulleys.append({"name": f"IDR{k // 2}", "role": "idler", "x_mm": round(0.8 * big * np.cos(a), 1),
                            "y_mm": round(0.8 * big * np.sin(a), 1), "pitch_diameter_mm": 77.2,
                            "effective_diameter_mm": 79.6, "backside": True, "inertia_kg_m2": 0.0002})
    powers = [{"WP": 0.5, "ALT": 2.0, "PS": 0.8, "A_C": 2.5, "FAN": 1.0, "AUX": 0.3},
              {"WP": 0.8, "ALT": 3.0, "PS": 1.0, "A_C": 3.5, "FAN": 2.0, "AUX": 0.4},
              {"WP": 1.1, "ALT": 4.0, "PS": 1.2, "A_C": 4.5, "FAN": 3.5, "AUX": 0.5},
              {"WP": 1.5, "ALT": 5.0, "PS": 1.4, "A_C": 5.5, "FAN": 5.0, "AUX": 0.6},
              {"WP": 2.0, "ALT": 5.5, "PS": 1.6, "A_C": 6.5, "FAN": 7.0, "AUX": 0.7},
              {"WP": 2.6, "ALT": 6.0, "PS": 1.8, "A_C": 7.0, "FAN": 9.0, "AUX": 0.8}]
    duty = [{"speed_rpm": s, "time_pct": t, "power_kw": {**p, "IDR1": 0.01, "IDR2": 0.01, "TEN": 0.01}}
            for s, t, p in zip((800, 1200, 1600, 2000, 2400, 2800), (20, 25, 20, 15, 12, 8), powers)]
    return {"name": "ten-pulley drive (benchmark)", "belt": {"ribs": 8, "length_tolerance_mm": 6, "wear_pct": 0.7},
            "pulleys": pulleys, "duty": duty,
            "tensioner": {"pivot_x_mm": 58.3, "pivot_y_mm": -290.7, "arm_length_mm": 70.0, "free_arm_angle_deg": 50.0,
                          "preload_nm": 45.0 - 0.45 * 25.0, "stiffness_nm_per_deg": 0.45, "nominal_torque_nm": 45.0,
                          "installation_angle_deg": -10.0, "inertia_kg_m2": 0.004, "pulley_mass_kg": 0.5}}


def _clear():
    from synth.drive.analysis import drive_model, drive_sweep
    from synth.drive.positions import frame
    frame.cache_clear()
    drive_model.cache_clear()
    drive_sweep.cache_clear()


def _best(fn, repeat):
    out = []
    for _ in range(repeat):
        _clear()
        t = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t)
    return min(out)


def _rows(label, data, repeat):
    from synth.drive.analysis import analyse
    from synth.drive.inputs import validate
    from synth.drive.positions import duty_table, positions
    drive = validate(data)
    n_pos = sum(r["found"] for r in positions(drive)["rows"])
    n_duty = len(drive.duty)
    times = {"validate (nominal solved)": _best(lambda: validate(data), repeat),
             "positions": _best(lambda: positions(drive), repeat),
             "duty table": _best(lambda: duty_table(drive), repeat),
             "positions + duty table": _best(lambda: (positions(drive), duty_table(drive)), repeat),
             "analyse (+ modes over the EA range)": _best(lambda: analyse(drive, check=False), repeat)}
    return [f"| {label} | {len(drive.pulleys)} | {n_pos} | {n_duty} | {what} | {t * 1000:.1f} |"
            for what, t in times.items()]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="one repeat, the ten-pulley drive only (a smoke test)")
    a = ap.parse_args(argv)
    repeat = 1 if a.quick else a.repeat
    import yaml
    lines = ["| drive | pulleys | positions | duty points | step | ms (best of %d) |" % repeat,
             "|---|---|---|---|---|---|"]
    lines += _rows("ten-pulley", ten_pulley_drive(), repeat)
    if not a.quick:
        for name in ("gates_ag00686", "gates_ag00810", "gates_ag00879", "gates_ag00976_1715"):
            data = yaml.safe_load((ROOT / "synth" / "data" / "drives" / f"{name}.yaml").read_text())
            lines += _rows(name, data, repeat)
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
