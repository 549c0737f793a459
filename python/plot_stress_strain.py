#!/usr/bin/env python3
"""Plot tensile-test curves (true stress [GPa] against logarithmic strain [-]) to a PNG file.

Reads one or more stress_strain.csv files written by `indentsim run` for `test: tensile`
(header row with at least the columns log_strain and true_stress_GPa), e.g. the crystal run and
its J2 comparison (stress_strain_j2.csv, written with compare_j2: true or --compare-j2).

Usage:
    python3 python/plot_stress_strain.py results/x/stress_strain.csv --label crystal \
        results/x/stress_strain_j2.csv --label j2 -o results/x/stress_strain.png

Units: true stress (volume-average Cauchy sigma_zz) in GPa, logarithmic strain dimensionless.
"""

import argparse
import csv
import os
import sys

from indentsim_plotting import ensure_matplotlib, save_figure  # noqa: E402

ensure_matplotlib("plot_stress_strain.py")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_curve(path):
    """Logarithmic strain [-] and true stress [GPa] columns of a stress_strain.csv file."""
    with open(path, newline="", encoding="utf-8-sig") as stream:
        rows = [row for row in stream if not row.lstrip().startswith("#")]
    reader = csv.DictReader(rows)
    if reader.fieldnames is None:
        raise ValueError(f"{path}: empty file, expected a header row with "
                         "log_strain,true_stress_GPa")
    fields = [name.strip() for name in reader.fieldnames]
    reader.fieldnames = fields
    for column in ("log_strain", "true_stress_GPa"):
        if column not in fields:
            raise ValueError(f"{path}: no column '{column}' (columns: {', '.join(fields)})")
    strain, stress = [], []
    for line_number, row in enumerate(reader, start=2):
        try:
            strain.append(float(row["log_strain"]))
            stress.append(float(row["true_stress_GPa"]))
        except (TypeError, ValueError):
            raise ValueError(f"{path}: row {line_number} has no numeric "
                             f"log_strain/true_stress_GPa: {row}")
    return np.array(strain), np.array(stress)


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Plot true stress [GPa] against logarithmic strain from stress_strain.csv "
                    "files.")
    parser.add_argument("csv", nargs="+", help="stress_strain.csv file(s)")
    parser.add_argument("-o", "--output", required=True, help="PNG file to write")
    parser.add_argument("--label", action="append", default=[],
                        help="legend label, once per CSV file in order (default: the file path)")
    parser.add_argument("--title", default="Uniaxial tension", help="plot title")
    args = parser.parse_intermixed_args(argv)

    if len(args.label) > len(args.csv):
        parser.error(f"{len(args.label)} labels for {len(args.csv)} CSV files")

    figure, axes = plt.subplots(figsize=(6.4, 4.8), dpi=150)
    for index, path in enumerate(args.csv):
        try:
            strain, stress = read_curve(path)
        except (OSError, ValueError) as error:
            print(f"plot_stress_strain.py: {error}", file=sys.stderr)
            return 1
        label = args.label[index] if index < len(args.label) else path
        axes.plot(strain, stress, marker="o", markersize=2.0, linewidth=1.2, label=label)

    axes.set_xlabel("logarithmic strain ln(1 + u_top / L) [-]")
    axes.set_ylabel("true stress (volume-average Cauchy $\\sigma_{zz}$) [GPa]")
    axes.set_title(args.title)
    axes.set_xlim(left=0.0)
    axes.set_ylim(bottom=0.0)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")
    return save_figure(figure, args.output, "plot_stress_strain.py")


if __name__ == "__main__":
    sys.exit(main())
