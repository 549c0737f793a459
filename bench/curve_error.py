#!/usr/bin/env python3
"""The error of loading curves of the paper's J2 case against its converged curve.

The converged curve of the paper's self-similar rounded cone on a material without a length
scale is P = C (h + delta)^2 with one C (23.065 GPa: the Richardson value of the step sequence of
bench/paper_j2_convergence.sh, docs/validation.md). For each run directory or
load_penetration.csv given, over the loading points with 1 <= h <= 6 um:

  pointwise   the smallest and largest P / (C (h + delta)^2) - 1 [%]
  mean        the mean of that ratio [%]
  RMS         sqrt of the mean over h (the integral over [1, 6] um / 5 um, the curve
              interpolated linearly between its points) of ((P - C (h + delta)^2) / P(6.0 um))^2
              [%]: the measure of docs/performance.md's comparison with an independent code
              ("RMS over 1-6 um, of the converged 6 um force")

and, from run_summary.json when it is there, DOFs, Newton iterations and the run's total time
(time_total_s).

    python3 bench/curve_error.py RUN_DIR_OR_CSV... [--c GPA] [--delta UM]

Units: um, mN, GPa, s.
"""
import argparse
import csv
import json
import math
import pathlib
import sys

# Linear interpolation as the study report does it (python/study_report.py).
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "python"))
from study_report import interpolate  # noqa: E402


def loading_points(csv_path):
    with open(csv_path, newline="") as handle:
        rows = list(csv.DictReader(line for line in handle if not line.startswith("#")))
    points = [(float(r["depth_um"]), float(r["force_mN"])) for r in rows
              if r.get("segment", "load") == "load"]
    return sorted(points)


def errors(points, c, delta):
    converged = lambda h: c * (h + delta) ** 2
    inside = [(h, p) for h, p in points if 1.0 - 1e-9 <= h <= 6.0 + 1e-9]
    if not inside or points[-1][0] < 6.0 - 1e-9 or points[0][0] > 1.0:
        raise ValueError("the loading curve does not span 1-6 um")
    ratio = [100 * (p / converged(h) - 1) for h, p in inside]
    # The mean over h of the squared error by the trapezoidal rule on 500 intervals.
    n = 500
    p6 = converged(6.0)
    depths, forces = [h for h, _ in points], [p for _, p in points]
    squares = [((interpolate(min(h, depths[-1]), depths, forces) - converged(h)) / p6) ** 2
               for h in (1.0 + 5.0 * i / n for i in range(n + 1))]
    rms = math.sqrt((sum(squares) - 0.5 * (squares[0] + squares[-1])) / n)
    return min(ratio), max(ratio), sum(ratio) / len(ratio), 100 * rms


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", help="run directories or load_penetration.csv files")
    parser.add_argument("--c", type=float, default=23.065, help="converged C [GPa]")
    parser.add_argument("--delta", type=float, default=0.005, help="the cone's delta [um]")
    args = parser.parse_args()
    print("| run | DOFs | Newton its | time [s] | pointwise [%] | mean [%] | RMS [% of P(6.0 um)] |")
    print("|---|---|---|---|---|---|---|")
    for run in args.runs:
        path = pathlib.Path(run)
        csv_path = path / "load_penetration.csv" if path.is_dir() else path
        try:
            low, high, mean, rms = errors(loading_points(csv_path), args.c, args.delta)
        except (OSError, KeyError, ValueError) as error:
            sys.exit(f"curve_error.py: {csv_path}: {error!r} (a load_penetration.csv with the "
                     "columns segment, depth_um and force_mN, loading from 1 um to 6 um is needed)")
        summary_path = csv_path.parent / "run_summary.json"
        dofs = newton = time = "-"
        if summary_path.exists():
            summary = json.loads(summary_path.read_text())
            dofs, newton = summary["dofs"], summary["newton_iterations"]
            time = f"{summary['time_total_s']:.1f}"
        print(f"| {csv_path.parent.name} | {dofs} | {newton} | {time} | {low:+.2f} ... {high:+.2f} | "
              f"{mean:+.2f} | {rms:.2f} |")


if __name__ == "__main__":
    main()
