"""Synthetic measured curve for the calibration tests: a run's load_penetration.csv with
Gaussian noise on every force, of standard deviation RELATIVE_NOISE times the largest force (the
equal-variance errors the calibration's intervals assume; seeded, reproducible).

Usage: add_noise.py RUN_CSV OUT_CSV SEED RELATIVE_NOISE
Units: depth um, force mN (as in the run's file)."""
import csv
import sys

import numpy as np


def main():
    source, target, seed, noise = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    rng = np.random.default_rng(seed)
    with open(source, newline="") as f:
        rows = list(csv.DictReader(f))
    sigma = noise * max(float(row["force_mN"]) for row in rows)
    with open(target, "w", newline="") as f:
        f.write("depth_um,force_mN\n")
        for row in rows:
            force = float(row["force_mN"]) + sigma * rng.standard_normal()
            f.write("%s,%.10g\n" % (row["depth_um"], force))


if __name__ == "__main__":
    main()
