#!/usr/bin/env python3
"""Tabulates the step and mesh sequence of bench/paper_j2_convergence.yaml.

For each run: DOFs, steps, C = P/(h + delta)^2 over the loading points with 1 <= h <= 6 um (its
mean, smallest and largest value), the force at 6.0 um, Newton iterations and wall time. For each
mesh with 192, 384 and 768 steps: the observed order p of the step sequence,
p = log2((C_384 - C_192) / (C_768 - C_384)) on the mean C, and the Richardson value
C_inf = C_768 + (C_768 - C_384) / (2^p - 1), with P(6.0 um) = C_inf (6.0 + delta)^2.

    python3 bench/paper_j2_convergence.py STUDY_DIR

Units: um, mN, GPa, s.
"""
import csv
import json
import math
import pathlib
import re
import sys

DELTA = 0.005  # [um] the rounded cone's offset of eq. 16 (examples/paper_j2_auto_axisymmetric.yaml)


def run_row(case_dir):
    rows = [r for r in csv.DictReader(open(case_dir / "load_penetration.csv"))
            if r["segment"] == "load"]
    c = [float(r["force_mN"]) / (float(r["depth_um"]) + DELTA) ** 2 for r in rows
         if 1.0 - 1e-9 <= float(r["depth_um"]) <= 6.0 + 1e-9]
    summary = json.load(open(case_dir / "run_summary.json"))
    return {"dofs": summary["dofs"], "mean": sum(c) / len(c), "low": min(c), "high": max(c),
            "force": summary["force_at_max_depth_mN"], "newton": summary["newton_iterations"],
            "time": summary["time_total_s"]}


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    runs = {}
    for case_dir in sorted(pathlib.Path(sys.argv[1], "cases").iterdir()):
        match = re.match(r"n(\d+)_s(\d+)-", case_dir.name)
        if match and (case_dir / "run_summary.json").exists():
            runs[(int(match.group(1)), int(match.group(2)))] = run_row(case_dir)
    if not runs:
        sys.exit(f"no finished runs under {sys.argv[1]}/cases")
    print("| n | steps | DOFs | mean C [GPa] | C over 1-6 um [GPa] | P(6.0 um) [mN] | Newton its | time [s] |")
    print("|---|---|---|---|---|---|---|---|")
    for (n, steps), r in sorted(runs.items()):
        print(f"| {n} | {steps} | {r['dofs']} | {r['mean']:.3f} | {r['low']:.2f}-{r['high']:.2f} | "
              f"{r['force']:.1f} | {r['newton']} | {r['time']:.1f} |")
    print()
    for n in sorted({n for n, _ in runs}):
        c = [runs.get((n, s), {}).get("mean") for s in (192, 384, 768)]
        if None in c:
            continue
        ratio = (c[1] - c[0]) / (c[2] - c[1])
        if ratio <= 1:
            print(f"n {n}: the step sequence does not converge monotonically (ratio {ratio:.2f})")
            continue
        p = math.log2(ratio)
        c_inf = c[2] + (c[2] - c[1]) / (2 ** p - 1)
        print(f"n {n}: observed order in the steps p = {p:.2f}; Richardson C = {c_inf:.3f} GPa, "
              f"P(6.0 um) = {c_inf * (6.0 + DELTA) ** 2:.1f} mN; 192 steps lie "
              f"{100 * (c[0] / c_inf - 1):+.2f} % (mean), "
              f"{100 * (runs[(n, 192)]['low'] / c_inf - 1):+.2f} ... "
              f"{100 * (runs[(n, 192)]['high'] / c_inf - 1):+.2f} % (pointwise) from it")


if __name__ == "__main__":
    main()
