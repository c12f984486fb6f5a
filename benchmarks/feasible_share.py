"""Feasible share of a generated portfolio by environment, and what binds (issue 12).

Run: ``.venv/bin/python benchmarks/feasible_share.py [N]`` (default 200 applications, seed 0, screening
fidelity, objective ``standard``). Prints, per environment, the feasible share and the constraints violated
by the infeasible applications; then the same applications with the environment switched (every other input
kept), which separates the physics of the environment from the portfolio's other inputs; then the share of the
target torque the main spring carries at nominal, ``T_s / T_c = 1 - D rho / T_c`` (eq. (12)-(13)).
"""

from __future__ import annotations

import collections
import dataclasses
import sys

import numpy as np

from synth.parts import mu
from synth.bulk.engine import screen_applications
from synth.data.generated_applications import generate
from synth.model import damping as D

ENVS = ("belt_in_oil", "dry")


def violated(df) -> collections.Counter:
    c = collections.Counter()
    for v in df.loc[~df["feasible"].astype(bool), "violated"]:
        for item in str(v).split(";"):
            if item and item != "nan":
                c[item.split(":")[0]] += 1
    return c


def spring_share(a, env: str, pivot_mm: float) -> float:
    rho = D.lever_ratio(pivot_mm, mu("pivot_bushing", env), a.working_arm_mm, a.differential_angle_deg)
    split = D.damping_split(a.calculated_torque_target_nm, a.damping_target_nm, rho)
    return float(split["spring_torque_nominal_nm"]) / a.calculated_torque_target_nm


def main(n: int = 200) -> None:
    apps = generate(n, seed=0)
    print(f"{n} generated applications (seed 0), screening fidelity, objective standard\n")
    print("| applications | evaluated as | n | feasible | most violated (infeasible applications) |")
    print("|---|---|---|---|---|")
    for env in ENVS:
        own = [a for a in apps if a.application_type == env]
        for as_env in (env, *(e for e in ENVS if e != env)):
            batch = [dataclasses.replace(a, application_type=as_env) for a in own]
            df = screen_applications(batch, objective="standard", fidelity="screening", diagnose=False)
            top = ", ".join(f"{k} {v}" for k, v in violated(df).most_common(6))
            print(f"| {env} | {as_env} | {len(own)} | {df['feasible'].mean():.0%} | {top} |")
    print("\nShare of the target torque the main spring carries at nominal (pivot 16 mm, friction circle):")
    print("| applications | as dry | as belt_in_oil |\n|---|---|---|")
    for env in ENVS:
        own = [a for a in apps if a.application_type == env]
        cells = [np.mean([spring_share(a, e, 16.0) for a in own]) for e in ("dry", "belt_in_oil")]
        print(f"| {env} | {cells[0]:.3f} | {cells[1]:.3f} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 200)
