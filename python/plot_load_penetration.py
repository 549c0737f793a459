#!/usr/bin/env python3
"""Plot indentation load-penetration curves (force [mN] against depth [um]) to a PNG file.

Reads one or more load_penetration.csv files written by `indentsim run` (header row with at
least the columns depth_um and force_mN) and optionally overlays Sneddon's closed-form elastic
solution for the rounded cone of eq. 16 (see docs/development.md):

    c = a * delta,  h(a_c) = (a_c / a) atan(a_c / c),
    P(a_c) = (E* / a) [ (a_c^2 - c^2) atan(a_c / c) + a_c c ].

Usage:
    python3 python/plot_load_penetration.py results/x/load_penetration.csv \
        -o results/x/load_penetration.png
    python3 python/plot_load_penetration.py a.csv b.csv --label "N=12" --label "N=24" \
        --reference 74.0026 2.48 0.005 -o compare.png

Units: depth in um, force in mN, E* in GPa (1 GPa*um^2 = 1 mN).
"""

import argparse
import csv
import math
import os
import sys

from indentsim_plotting import ensure_matplotlib, save_figure  # noqa: E402

ensure_matplotlib("plot_load_penetration.py")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_curve(path):
    """Depth [um] and force [mN] columns of a load_penetration.csv file."""
    with open(path, newline="", encoding="utf-8-sig") as stream:
        rows = [row for row in stream if not row.lstrip().startswith("#")]
    reader = csv.DictReader(rows)
    if reader.fieldnames is None:
        raise ValueError(f"{path}: empty file, expected a header row with depth_um,force_mN")
    fields = [name.strip() for name in reader.fieldnames]
    reader.fieldnames = fields
    for column in ("depth_um", "force_mN"):
        if column not in fields:
            raise ValueError(f"{path}: no column '{column}' (columns: {', '.join(fields)})")
    depth, force = [], []
    for line_number, row in enumerate(reader, start=2):
        try:
            depth.append(float(row["depth_um"]))
            force.append(float(row["force_mN"]))
        except (TypeError, ValueError):
            raise ValueError(f"{path}: row {line_number} has no numeric depth_um/force_mN: {row}")
    return np.array(depth), np.array(force)


def sneddon_force(depth, reduced_modulus, a, delta):
    """Closed-form force [mN] at the given depths [um] (elastic half-space, rigid indenter)."""
    depth = np.asarray(depth, dtype=float)
    force = np.zeros_like(depth)
    positive = depth > 0.0
    h = depth[positive]
    if delta == 0.0:  # sharp cone: P = (2/pi) E* a h^2
        force[positive] = 2.0 / math.pi * reduced_modulus * a * h**2
        return force
    c = a * delta
    # Solve x atan(x) = h / delta for x = a_c / c by bisection (vectorized, monotone).
    target = h / delta
    lo = np.zeros_like(target)
    hi = np.maximum(1.0, 2.0 * target)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        below = mid * np.arctan(mid) < target
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    x = 0.5 * (lo + hi)
    # (x^2 - 1) atan x + x cancels for small x: use its series there.
    series = sum((-1) ** (k - 1) * 4.0 * k / (4.0 * k * k - 1.0) * x ** (2 * k + 1)
                 for k in range(1, 13))
    shape = np.where(x < 0.1, series, (x * x - 1.0) * np.arctan(x) + x)
    force[positive] = reduced_modulus * c * c / a * shape
    return force


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Plot force [mN] against depth [um] from load_penetration.csv files.")
    parser.add_argument("csv", nargs="+", help="load_penetration.csv file(s)")
    parser.add_argument("-o", "--output", required=True, help="PNG file to write")
    parser.add_argument("--label", action="append", default=[],
                        help="legend label, once per CSV file in order (default: the file path)")
    parser.add_argument("--reference", nargs=3, type=float, metavar=("E_STAR", "A", "DELTA"),
                        help="overlay the closed-form Sneddon curve for E* [GPa], slope a [-] and "
                             "tip rounding delta [um]")
    parser.add_argument("--title", default="Load-penetration curve", help="plot title")
    args = parser.parse_args(argv)

    if len(args.label) > len(args.csv):
        parser.error(f"{len(args.label)} labels for {len(args.csv)} CSV files")
    if args.reference is not None:
        reduced_modulus, a, delta = args.reference
        if reduced_modulus <= 0 or a <= 0 or delta < 0:
            parser.error("--reference needs E* > 0, a > 0 and delta >= 0")

    figure, axes = plt.subplots(figsize=(6.4, 4.8), dpi=150)
    max_depth = 0.0
    for index, path in enumerate(args.csv):
        try:
            depth, force = read_curve(path)
        except (OSError, ValueError) as error:
            print(f"plot_load_penetration.py: {error}", file=sys.stderr)
            return 1
        label = args.label[index] if index < len(args.label) else path
        axes.plot(depth, force, marker="o", markersize=2.5, linewidth=1.2, label=label)
        if depth.size:
            max_depth = max(max_depth, float(np.max(depth)))

    if args.reference is not None:
        reduced_modulus, a, delta = args.reference
        depth = np.linspace(0.0, max_depth if max_depth > 0 else 1.0, 400)
        axes.plot(depth, sneddon_force(depth, reduced_modulus, a, delta), "k--", linewidth=1.0,
                  label=f"Sneddon, elastic (E* = {reduced_modulus:g} GPa, a = {a:g}, "
                        f"delta = {delta:g} um)")

    axes.set_xlabel("depth [um]")
    axes.set_ylabel("force [mN]")
    axes.set_title(args.title)
    axes.set_xlim(left=0.0)
    axes.set_ylim(bottom=0.0)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")
    return save_figure(figure, args.output, "plot_load_penetration.py")


if __name__ == "__main__":
    sys.exit(main())
