#!/usr/bin/env python3
"""Runs a shipped example and compares its curve with the gold file (CTest label regression).

Requirement: `indentsim run EXAMPLE` reproduces the example's gold curve
(tests/regression/gold/<example>.csv): the same number of rows, and in every compared column
every row within `--relative-tolerance` times the largest magnitude of that column in the gold
file. The scale is the column's largest value, not the row's own, because the force passes
through zero at the end of unloading. The test only reads the gold file; scripts/regenerate_gold.sh
writes it.

Usage: check_gold.py INDENTSIM CASE.yaml OUTPUT_DIR CSV_NAME GOLD.csv COLUMNS TOLERANCE
  COLUMNS: comma-separated column names (e.g. depth_um,force_mN); TOLERANCE: relative, e.g. 1e-6.
"""

import csv
import subprocess
import sys


def read_columns(path, names):
    """The named columns of a CSV file (lines starting with '#' are comments)."""
    with open(path, newline="") as handle:
        rows = [row for row in csv.reader(line for line in handle if not line.startswith("#"))]
    header, body = rows[0], rows[1:]
    missing = [name for name in names if name not in header]
    if missing:
        raise SystemExit(f"FAIL: {path} lacks the column(s) {', '.join(missing)}")
    return {name: [float(row[header.index(name)]) for row in body] for name in names}


def compare(computed, gold, tolerance):
    """Failure messages, one per column that leaves the tolerance; empty if the curves agree."""
    failures = []
    for name, reference in gold.items():
        values = computed[name]
        if len(values) != len(reference):
            failures.append(f"{name}: {len(values)} rows, the gold file has {len(reference)}")
            continue
        scale = max(abs(v) for v in reference) or 1.0
        worst_row, worst = max(enumerate(abs(a - b) for a, b in zip(values, reference)),
                               key=lambda item: item[1], default=(0, 0.0))
        print(f"{name}: largest difference {worst:.3e} (row {worst_row}), "
              f"{worst / scale:.3e} of the column's largest magnitude {scale:.6g}")
        if worst > tolerance * scale:
            failures.append(f"{name}: row {worst_row} computed {values[worst_row]!r}, "
                            f"gold {reference[worst_row]!r}, beyond {tolerance:g} x {scale:.6g}")
    return failures


def main(argv):
    if len(argv) != 8:
        raise SystemExit(__doc__)
    indentsim, case_file, output, csv_name, gold_file, columns, tolerance = argv[1:]
    names = columns.split(",")
    run = subprocess.run([indentsim, "run", case_file, "--output", output, "--overwrite"])
    if run.returncode != 0:
        raise SystemExit(f"FAIL: indentsim run {case_file} exited with {run.returncode}")
    failures = compare(read_columns(f"{output}/{csv_name}", names),
                       read_columns(gold_file, names), float(tolerance))
    if failures:
        raise SystemExit("FAIL: the curve left its gold file " + gold_file + ":\n  " +
                         "\n  ".join(failures))
    print(f"OK: {case_file} matches {gold_file} to {tolerance} relative")


if __name__ == "__main__":
    main(sys.argv)
